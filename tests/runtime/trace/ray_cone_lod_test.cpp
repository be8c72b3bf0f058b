// Ray-cone LOD (thesis §2.2, eq. 2.10-2.16): a checker texture on a plane facing the camera
// at growing distances is sampled at the mip level the formula predicts. Each mip level of
// the test texture has its own red value (level / (levels - 1)) under a green checker, so
// the red channel of the emitted colour reads back the (trilinearly blended) level. In both
// architectures.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

constexpr std::uint32_t kTextureSize = 256;
constexpr int kLevels = 9;  // 256 .. 1

constexpr const char* kCheckerGraph = R"(material Checker;
UVInput UV>0;
ImageTexture Image="checker.pfm" UV<0 Color>1;
EmissionOutput Color<1;
BaseColorOutput Color=(0, 0, 0);
)";

class RayConeLod : public ::testing::TestWithParam<Shading> {};

TEST_P(RayConeLod, CheckerAtGrowingDistanceSelectsPredictedMip) {
  const float planeSize = 4.0f;
  const float fovDegrees = 30.0f;
  const std::uint32_t size = 33;  // odd: the centre pixel's ray is the optical axis
  std::vector<std::string> requested;
  RendererOptions options = testing::testOptions();
  options.shading = GetParam();
  options.textureLoader = [&](const std::string& path) {
    requested.push_back(path);
    return testing::levelTaggedChecker(kTextureSize, kLevels, 4);
  };
  Renderer renderer(options);

  double previous = -1.0;
  for (float distance : {2.0f, 8.0f, 32.0f, 128.0f}) {
    Scene scene;
    scene.meshes.push_back(testing::quad(planeSize));
    scene.materials.push_back({"Checker", "", kCheckerGraph});
    // Stand the plane up to face +z.
    glm::mat4 toWorld = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
    scene.instances.push_back({0, 0, toWorld});
    scene.camera.position = {0, 0, distance};
    scene.camera.target = {0, 0, 0};
    scene.camera.verticalFovDegrees = fovDegrees;
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.raysPerPath = 1;
    settings.sharedPrimaryRay = true;
    RenderResult result = renderer.render(scene, settings);

    // Eq. 2.10 with w_old = 0: w = alpha * t, alpha = atan(2 tan(fov/2) / H). Head-on, both
    // footprint axes span w (one pixel) in world units, i.e. w / planeSize in UV.
    double alpha = std::atan(2.0 * std::tan(fovDegrees * 0.5 * 3.14159265358979 / 180.0) / size);
    double uvFootprint = alpha * distance / planeSize;
    double predicted = std::clamp(std::log2(uvFootprint * kTextureSize), 0.0, kLevels - 1.0);
    double measured = result.image.pixel(size / 2, size / 2)[0] * (kLevels - 1);
    std::printf("ray-cone LOD: distance %6.1f predicted level %.3f measured %.3f\n", distance,
                predicted, measured);
    EXPECT_NEAR(measured, predicted, 0.2);
    EXPECT_GT(measured, previous);
    previous = measured;
    EXPECT_TRUE(renderer.context().validationErrors().empty());
  }
  ASSERT_FALSE(requested.empty());
  EXPECT_EQ(requested.front(), "checker.pfm");
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, RayConeLod,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

}  // namespace
}  // namespace memograph::runtime
