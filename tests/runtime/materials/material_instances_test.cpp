// Material instances (runtime/materials/material_instances.h): distinct graphs that differ only
// in float constants share one wavefront material pass, reading the constants that differ from
// their bin's parameter block. Pinned: which graphs group and which constants become
// parameters, the parameter buffer's layout, and that a shared pass renders what each graph's
// own pass renders.
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/materials/material_instances.h"
#include "runtime/materials/material_linker.h"
#include "runtime/renderer.h"

namespace memograph::runtime {
namespace {

TEST(MaterialInstances, GraphsOfOneShapeGroupAndTheirDifferingConstantsBecomeParameters) {
  const std::vector<InstanceCandidate> candidates = {
      {"A", {{1.0f}, {0.1f, 0.2f, 0.3f}, {7.0f}}},
      {"B", {{2.0f}}},
      {"A", {{1.0f}, {0.4f, 0.5f, 0.6f}, {8.0f}}},
      {"A", {{1.0f}, {0.1f, 0.2f, 0.3f}, {9.0f}}},
  };
  const auto groups = groupMaterialInstances(candidates);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].members, (std::vector<std::uint32_t>{0, 2, 3}));
  // The first constant is the same in all three: a literal still.
  EXPECT_EQ(groups[0].parameterConstants, (std::vector<bool>{false, true, true}));
  EXPECT_EQ(groups[0].parameterCount, 4u);
  EXPECT_EQ(groups[0].parameters, (std::vector<float>{0.1f, 0.2f, 0.3f, 7.0f, 0.4f, 0.5f, 0.6f,
                                                      8.0f, 0.1f, 0.2f, 0.3f, 9.0f}));
  EXPECT_EQ(groups[1].members, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(groups[1].parameterCount, 0u);
}

TEST(MaterialInstances, MinusZeroIsAnotherConstant) {
  const auto groups = groupMaterialInstances({{"A", {{0.0f}}}, {"A", {{-0.0f}}}});
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].parameterConstants, (std::vector<bool>{true}));
}

// A recipe's material: uv noise between two colours, with its own offset, scale, colours and
// roughness; `stretched` puts one node more before the noise, another shape.
std::string recipeGraph(const std::string& name, float offset, float scale, glm::vec3 a,
                        glm::vec3 b, float roughness, bool stretched = false) {
  std::ostringstream text;
  text << "material " << name << ";\n"
       << "UVInput Out>0;\n"
       << "Add A<0 B=(" << offset << ", 0.25, 0.0) Out>1;\n";
  if (stretched)
    text << "Mul A<1 B=(2.0, 1.0, 1.0) Out>9;\n";
  text << "NoiseTexture Vector<" << (stretched ? 9 : 1) << " Scale=" << scale
       << " Detail=4.0 Roughness=0.5 Fac>2;\n"
       << "Mix A=(" << a.x << ", " << a.y << ", " << a.z << ") B=(" << b.x << ", " << b.y << ", "
       << b.z << ") Factor<2 Out>3;\n"
       << "BaseColorOutput In<3;\n"
       << "RoughnessOutput In=" << roughness << ";\n";
  return text.str();
}

std::vector<MaterialRef> recipeMaterials() {
  return {
      {"Red", "", recipeGraph("Red", 0.0f, 6.0f, {0.8f, 0.1f, 0.1f}, {0.3f, 0.0f, 0.0f}, 0.4f)},
      {"Green", "",
       recipeGraph("Green", 3.5f, 11.0f, {0.1f, 0.8f, 0.1f}, {0.0f, 0.3f, 0.0f}, 0.6f)},
      {"Finer", "",
       recipeGraph("Finer", 1.0f, 6.0f, {0.8f, 0.8f, 0.1f}, {0.3f, 0.3f, 0.0f}, 0.4f, true)},
      {"Blue", "", recipeGraph("Blue", 7.25f, 6.0f, {0.1f, 0.1f, 0.8f}, {0.0f, 0.0f, 0.3f}, 0.4f)},
  };
}

TEST(MaterialInstances, TheLinkerSharesAPassAmongARecipesGraphs) {
  const LinkedMaterials linked = linkMaterials(recipeMaterials());
  ASSERT_EQ(linked.distinct.size(), 4u);
  // Red, Green and Blue differ only in float constants; Finer has a node more, so it has a
  // pass of its own.
  ASSERT_EQ(linked.instanceGroups.size(), 2u);
  const MaterialInstanceGroup& shared = linked.instanceGroups[0];
  EXPECT_EQ(shared.name, "Red");
  EXPECT_EQ(shared.instances.members, (std::vector<std::uint32_t>{0, 1, 3}));
  // The offset's x (a float3: 3 floats), the scale, both colours and the roughness differ;
  // the offset's y and z, Detail and the noise's Roughness are the same in all three: they
  // stay literals, which the driver folds.
  EXPECT_EQ(shared.instances.parameterCount, 3u + 1u + 3u + 3u + 1u);
  EXPECT_NE(shared.include.find("MG_MATERIAL_PARAMETER("), std::string::npos);
  EXPECT_EQ(linked.instanceGroups[1].instances.members, (std::vector<std::uint32_t>{2}));
  EXPECT_EQ(linked.instanceGroups[1].include, linked.distinct[2].include);
  EXPECT_EQ(linked.distinct[2].include.find("MG_MATERIAL_PARAMETER("), std::string::npos);

  // Each member's block in member order: Green's scale is its 4th float (after the offset).
  EXPECT_EQ(shared.instances.parameters[shared.instances.parameterCount + 3], 11.0f);
}

// The shared pass renders each graph as its own pass does, up to float rounding: a constant
// read from the buffer instead of folded into the code (lavapipe; 4 quads, one per material).
// Renders `materials` on quads in a 2-wide grid, in the wavefront, with material instances and
// without (each graph its own pass).
struct InstancesAndOwnPasses {
  RenderResult shared;
  RenderResult own;
};
Scene quadsOf(const std::vector<MaterialRef>& materials) {
  Scene scene;
  scene.meshes.push_back(testing::quad(1.0f));
  scene.materials = materials;
  for (std::uint32_t m = 0; m < scene.materials.size(); ++m)
    scene.instances.push_back(
        {0, m,
         glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f + static_cast<float>(m % 2), 0.0f,
                                                   -0.5f + static_cast<float>(m / 2)))});
  scene.camera.position = {0, 3, 1};
  scene.environment.constantRadiance = {1.0f, 1.0f, 1.0f};  // the quads lit by a white sky
  return scene;
}
RenderSettings quadSettings() {
  RenderSettings settings;
  settings.width = 24;
  settings.height = 16;
  settings.pathsPerPixel = 2;
  settings.raysPerPath = 2;
  return settings;
}
RendererOptions wavefrontOptions(TextureLoader textures = loadTextureCore) {
  RendererOptions options = testing::testOptions(Backend::RayQuery);
  options.nodeLibraryDirectory.clear();  // the real node library
  options.shading = Shading::Wavefront;
  options.textureLoader = std::move(textures);
  return options;
}
InstancesAndOwnPasses renderBothWays(const std::vector<MaterialRef>& materials,
                                     TextureLoader textures = loadTextureCore) {
  const Scene scene = quadsOf(materials);
  RendererOptions options = wavefrontOptions(std::move(textures));
  InstancesAndOwnPasses result;
  result.shared = Renderer(options).render(scene, quadSettings());
  options.materialInstances = false;
  result.own = Renderer(options).render(scene, quadSettings());
  return result;
}

TEST(MaterialInstances, ASharedPassRendersWhatEachGraphsOwnPassRenders) {
  const auto [shared, own] = renderBothWays(recipeMaterials());
  EXPECT_EQ(shared.stats.wavefrontMaterialPasses, 2u);
  EXPECT_EQ(own.stats.wavefrontMaterialPasses, 4u);
  EXPECT_EQ(shared.stats.pipelinesCreated + 2u, own.stats.pipelinesCreated);
  const auto difference = testing::roundingDifference(shared.image, own.image);
  EXPECT_GT(difference.referenceMean, 0.05);
  EXPECT_LT(difference.largest, 1e-4 * difference.referenceMean + 1e-6);
}

// With ownMaterialPassesFromSecondFrame the first frame binds the shared passes and, before
// the second, each graph of a shared pass gets its own: from then on a frame renders to the
// bit what the instances-off render's does. Each frame alone, so the image is the last
// frame's; the shared pass's rounding makes its frame differ, so the comparison can fail.
TEST(MaterialInstances, GraphsGetTheirOwnPassesBeforeTheSecondFrame) {
  const Scene scene = quadsOf(recipeMaterials());
  RenderSettings settings = quadSettings();
  settings.frames = 3;
  settings.eachFrameAlone = true;
  RendererOptions options = wavefrontOptions();
  const RenderResult sharedThroughout = Renderer(options).render(scene, settings);
  EXPECT_EQ(sharedThroughout.stats.deferredPipelinesCreated, 0u);  // lavapipe: not by default

  options.ownMaterialPassesFromSecondFrame = true;
  const RenderResult deferred = Renderer(options).render(scene, settings);
  // Red, Green and Blue share the set-up's pass; Finer's own pass stays.
  EXPECT_EQ(deferred.stats.wavefrontMaterialPasses, 2u);
  EXPECT_EQ(deferred.stats.deferredPipelinesCreated, 3u);
  EXPECT_EQ(deferred.stats.pipelinesCreated, sharedThroughout.stats.pipelinesCreated);

  options.materialInstances = false;
  const RenderResult ownThroughout = Renderer(options).render(scene, settings);
  EXPECT_EQ(ownThroughout.stats.deferredPipelinesCreated, 0u);  // nothing was shared
  const auto sharedAgainstOwn =
      testing::roundingDifference(ownThroughout.image, sharedThroughout.image);
  ASSERT_GT(sharedAgainstOwn.largest, 0.0);
  EXPECT_EQ(testing::roundingDifference(ownThroughout.image, deferred.image).largest, 0.0);

  // A one-frame render has no second frame to prepare for.
  options.materialInstances = true;
  settings.frames = 1;
  EXPECT_EQ(Renderer(options).render(scene, settings).stats.deferredPipelinesCreated, 0u);
}

// Graphs of one shape that sample different images: the code names no image, only the graph's
// texture slots, so they share a pass, and each bin must sample from its own first slot (the
// word its dispatch pushes).
TEST(MaterialInstances, EachBinOfASharedPassSamplesItsOwnTextures) {
  auto textured = [](const std::string& name, const std::string& image, float gain) {
    std::ostringstream text;
    text << "material " << name << ";\nUVInput Out>0;\nImageTexture \"" << image
         << "\" UV<0 Color>1;\nMul A<1 B=" << gain << " Out>2;\nBaseColorOutput In<2;\n";
    return MaterialRef{name, "", text.str()};
  };
  const auto [shared, own] =
      renderBothWays({textured("Red", "red.pfm", 0.9f), textured("Blue", "blue.pfm", 0.8f)},
                     [](const std::string& path) {
                       return testing::flatTexture(path == "red.pfm" ? glm::vec3(0.9f, 0.1f, 0.1f)
                                                                     : glm::vec3(0.1f, 0.1f, 0.9f));
                     });
  EXPECT_EQ(shared.stats.wavefrontMaterialPasses, 1u);
  EXPECT_EQ(own.stats.wavefrontMaterialPasses, 2u);
  // Both colours show: a bin that sampled the other's slot would turn its quad the other hue.
  double red = 0.0, blue = 0.0;
  for (std::size_t i = 0; i + 3 < shared.image.rgba.size(); i += 4) {
    red += shared.image.rgba[i];
    blue += shared.image.rgba[i + 2];
  }
  EXPECT_GT(red, 0.0);
  EXPECT_GT(blue, 0.0);
  const auto difference = testing::roundingDifference(shared.image, own.image);
  EXPECT_GT(difference.referenceMean, 0.05);
  EXPECT_LT(difference.largest, 1e-4 * difference.referenceMean + 1e-6);
}

// A group whose differing constants do not fit the push constants after the WavefrontPush
// (80 floats: 48 + 320 bytes, past the 256 bytes of lavapipe and of most GPUs) gets a pass per
// graph, which renders as the instances-off run does.
TEST(MaterialInstances, AGroupWiderThanThePushConstantsGetsAPassPerGraph) {
  auto wide = [](const std::string& name, float tint) {
    std::ostringstream text;
    text << "material " << name << ";\nUVInput Out>0;\nSeparate2 Vector<0 X>1 Y>2;\n";
    // 27 mixes, each towards a colour of its own: 81 floats that differ between the graphs.
    int previous = -1;
    for (int k = 0; k < 27; ++k) {
      const float c = tint + 0.01f * static_cast<float>(k);
      if (previous < 0)
        text << "Mix A=(0.5, 0.5, 0.5)";
      else
        text << "Mix A<" << previous;
      text << " B=(" << c << ", " << 0.5f * c << ", " << 1.0f - c << ") Factor<" << (k % 2 ? 1 : 2)
           << " Out>" << 10 + k << ";\n";
      previous = 10 + k;
    }
    text << "BaseColorOutput In<" << previous << ";\n";
    return MaterialRef{name, "", text.str()};
  };
  const auto [shared, own] = renderBothWays({wide("Warm", 0.6f), wide("Cool", 0.2f)});
  EXPECT_EQ(shared.stats.wavefrontMaterialPasses, 2u);
  EXPECT_EQ(own.stats.wavefrontMaterialPasses, 2u);
  EXPECT_EQ(shared.stats.pipelinesCreated, own.stats.pipelinesCreated);
  const auto difference = testing::roundingDifference(shared.image, own.image);
  EXPECT_GT(difference.referenceMean, 0.05);
  EXPECT_EQ(difference.largest, 0.0);
}

}  // namespace
}  // namespace memograph::runtime
