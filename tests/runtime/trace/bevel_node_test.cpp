// The Bevel node in a material (a traced input, docs/design/traced-inputs.md): the megakernel
// traces its disk rays before the graph runs and averages the normals of the object's own
// surfaces within Radius. A cube's top face, seen from above, emits its Bevel normal: farther
// than Radius from every edge the normal is the face's exactly (any other surface's hits lie
// beyond the cubic falloff's reach), and near the front edge it tilts towards the front face.
// On both trace backends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

constexpr float kRadius = 0.1f;

// The top face (y = 0.5) from straight above, z from about 0.11 to 0.49: the front edge
// (z = 0.5) just outside the image.
Scene cubeTopScene() {
  Scene scene;
  scene.meshes.push_back(testing::unitCube());
  scene.materials.push_back({"Rounded", "",
                             "material Rounded;\n"
                             "Bevel Radius=0.1 Samples=16 Normal>1;\n"
                             "EmissionOutput Color<1 Strength=1.0;\n"
                             "BaseColorOutput In=(0.0, 0.0, 0.0);\n"
                             "SpecularOutput In=0.0;\n"});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.camera.position = {0.0f, 3.0f, 0.3f};
  scene.camera.target = {0.0f, 0.5f, 0.3f};
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.verticalFovDegrees = 8.6f;
  return scene;
}

// The z of the top face's point seen through the centre of pixel row `y` (the camera looks
// straight down with up = -z, so a row is a z).
double topFaceZOfRow(const Camera& camera, int y, int size) {
  const double tanHalf = std::tan(glm::radians(double(camera.verticalFovDegrees)) * 0.5);
  const double ndcY = (y + 0.5) / size * 2.0 - 1.0;
  const double height = double(camera.position.y) - 0.5;
  // Direction forward - ndcY * tanHalf * up, up = (0, 0, -1): z grows with ndcY.
  return double(camera.position.z) + ndcY * tanHalf * height;
}

class BevelNode : public ::testing::TestWithParam<Backend> {};

TEST_P(BevelNode, FacesKeepTheirNormalAndEdgesTilt) {
  const Scene scene = cubeTopScene();
  RendererOptions options = testing::testOptions(GetParam());
  options.nodeLibraryDirectory.clear();  // the real node library, which has Bevel
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 1;  // the top face's emission: its Bevel normal
  const RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  int far = 0, near = 0;
  double nearTilt = 0.0;
  for (int y = 0; y < 32; ++y) {
    const double z = topFaceZOfRow(scene.camera, y, 32);
    ASSERT_LT(z, 0.5) << "row " << y << " is past the front edge";
    for (int x = 0; x < 32; ++x) {
      const auto p = result.image.pixel(x, y);
      if (0.5 - z > kRadius + 0.01) {
        // The face's own normal, (0, 1, 0), up to float rounding.
        EXPECT_NEAR(p[0], 0.0, 1e-5) << x << "," << y;
        EXPECT_NEAR(p[1], 1.0, 1e-5) << x << "," << y;
        EXPECT_NEAR(p[2], 0.0, 1e-5) << x << "," << y;
        ++far;
      } else if (0.5 - z < 0.5 * kRadius) {
        // Towards the front face (0, 0, 1), never away from it.
        EXPECT_GE(p[2], 0.0) << x << "," << y;
        EXPECT_NEAR(p[0], 0.0, 0.05) << x << "," << y;
        nearTilt += p[2];
        ++near;
      }
    }
  }
  std::printf("Bevel: %d pixels far from the edge, %d near it (mean z tilt %.3f)\n", far, near,
              near ? nearTilt / near : 0.0);
  EXPECT_GT(far, 32 * 16);
  EXPECT_GE(near, 32 * 2);
  EXPECT_GT(nearTilt / near, 0.05);
}

INSTANTIATE_TEST_SUITE_P(BothBackends, BevelNode,
                         ::testing::Values(Backend::RayQuery, Backend::RayTracingPipeline),
                         [](const auto& info) {
                           return std::string(info.param == Backend::RayQuery ? "query"
                                                                              : "pipeline");
                         });

}  // namespace
}  // namespace memograph::runtime
