// Emissive-triangle NEE takes a constant emitter's emission from its light record instead of
// evaluating the graph at the light sample (path_tracer.glsl, sampleEmissiveTriangle). Both
// routes draw the same random numbers, so a declared constant that its graph bears out must
// give the very image the evaluated graph gives, for a two-sided emitter and for an area
// lamp's one-sided quad seen from the front and from behind.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

using Kind = MaterialRef::EmissionKind;

// A grey floor under a 1 m emissive panel at height 1.5, facing down (lighting the floor)
// or up (the floor behind it). Direct light only: one ray per path, so the floor's light
// comes from NEE alone.
HdrImage renderPanel(const std::string& emitterBody, Kind kind, bool facingDown) {
  Scene scene;
  scene.meshes.push_back(testing::quad(6.0f));
  scene.meshes.push_back(testing::quad(1.0f));
  scene.materials.push_back(
      {"Floor", "",
       "material Floor;\nBaseColorOutput In=(0.5, 0.5, 0.5);\nRoughnessOutput In=1;\n"});
  MaterialRef panel;
  panel.name = "Panel";
  panel.graphText = "material Panel;\n" + emitterBody + "BaseColorOutput In=(0, 0, 0);\n";
  panel.emissionEstimate = glm::vec3(5.0f);
  panel.emissionKind = kind;
  scene.materials.push_back(panel);
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  glm::mat4 place = glm::translate(glm::mat4(1.0f), {0.0f, 1.5f, 0.0f});
  if (facingDown)
    place = glm::rotate(place, glm::radians(180.0f), glm::vec3(1, 0, 0));
  scene.instances.push_back({1, 1, place});
  scene.camera.position = {0, 1.0f, 4.0f};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 50.0f;

  RendererOptions options = testing::testOptions();
  options.nodeLibraryDirectory.clear();  // the embedded library (BackfacingInput)
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.raysPerPath = 1;
  settings.pathsPerPixel = 4;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return result.image;
}

double largestDifference(const HdrImage& a, const HdrImage& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, double(std::abs(a.rgba[i] - b.rgba[i])));
  return worst;
}

const char* kTwoSided = "EmissionOutput Color=(5, 5, 5) Strength=1;\n";
const char* kFrontOnly =
    "BackfacingInput Out>0;\n"
    "Math Value=1 Value1<0 Value2=0 Operation=1 UseClamp=0 Result>1;\n"
    "EmissionOutput Color=(5, 5, 5) Strength<1;\n";

TEST(EmissiveNee, ConstantEmissionGivesTheEvaluatedGraphsImage) {
  const HdrImage constant = renderPanel(kTwoSided, Kind::Constant, true);
  const HdrImage evaluated = renderPanel(kTwoSided, Kind::Graph, true);
  const double floorLight = testing::meanChannel(constant, 0, 0, 12, 16, 16);
  EXPECT_GT(floorLight, 0.01) << "the panel lights the floor";
  EXPECT_LT(largestDifference(constant, evaluated), 1e-4 * std::max(1.0, floorLight));
}

TEST(EmissiveNee, OneSidedConstantEmissionLightsOnlyItsFront) {
  for (bool facingDown : {true, false}) {
    const HdrImage constant = renderPanel(kFrontOnly, Kind::ConstantFront, facingDown);
    const HdrImage evaluated = renderPanel(kFrontOnly, Kind::Graph, facingDown);
    const double floorLight = testing::meanChannel(constant, 0, 0, 12, 16, 16);
    if (facingDown)
      EXPECT_GT(floorLight, 0.01) << "the quad's front lights the floor";
    else
      EXPECT_LT(floorLight, 1e-6) << "the floor is behind the quad";
    EXPECT_LT(largestDifference(constant, evaluated), 1e-4 * std::max(1.0, floorLight))
        << (facingDown ? "facing down" : "facing up");
  }
}

}  // namespace
}  // namespace memograph::runtime
