// White furnace (thesis §2.1 BRDF): an albedo-1, roughness-1 dielectric sphere under a
// uniform white environment reflects about all light, so every pixel is about 1.
#include <gtest/gtest.h>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

TEST(WhiteFurnace, AlbedoOneSphereUnderWhiteSkyRendersOne) {
  Scene scene;
  scene.meshes.push_back(testing::sphere(32));
  scene.materials.push_back({"White", "", testing::constantGraph("White", {1, 1, 1}, 1.0f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.environment.constantRadiance = glm::vec3(1.0f);
  scene.camera.position = {0, 0, 3};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 45.0f;

  Renderer renderer(testing::testOptions());
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.pathsPerPixel = 4;
  settings.raysPerPath = 3;
  settings.frames = 4;
  RenderResult result = renderer.render(scene, settings);

  // The sphere covers the centre; its pixels average 16 paths each. Tolerance 0.03: the
  // estimator's spread over 16 x 100 paths (~0.5%) plus the dielectric layer's deviation
  // from exact energy conservation (the 4% Schlick specular on a 96% diffuse base, ~1-2%).
  double sphereMean = testing::meanChannel(result.image, 1, 12, 12, 20, 20);
  std::printf("white furnace: sphere mean %.4f, corner %.4f\n", sphereMean,
              result.image.pixel(0, 0)[1]);
  EXPECT_NEAR(sphereMean, 1.0, 0.03);
  EXPECT_FLOAT_EQ(result.image.pixel(0, 0)[1], 1.0f);  // background: the sky itself
  for (int y = 12; y < 20; ++y)
    for (int x = 12; x < 20; ++x)
      EXPECT_NEAR(result.image.pixel(x, y)[0], 1.0, 0.3);  // one pixel: 16 paths
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
