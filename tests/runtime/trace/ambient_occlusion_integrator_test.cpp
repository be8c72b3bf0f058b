// The AO integrator (--integrator ao, seeds/004 §3) against the analytic answer: a point of
// a plane under a sphere that lies wholly above its horizon. A sphere of radius r whose
// centre is at distance d, at angle theta from the normal, covers the projected solid angle
// pi (r/d)^2 cos(theta) (a cap's projected area on the unit disk), so the cosine-weighted
// unoccluded fraction is 1 - (r/d)^2 cos(theta). Uniform hemisphere sampling would give
// 1 - (1 - cos(alpha)) at the zenith instead: about 0.1 apart here, far outside the
// tolerances below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

constexpr float kSphereRadius = 0.5f;
constexpr float kSphereHeight = 1.0f;  // its centre above the plane y = 0

// A 20 m plane, the sphere above its origin, and a camera looking down at the origin
// through a narrow field of view (every pixel sees the plane, none the sphere).
Scene planeUnderSphere() {
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.meshes.push_back(testing::sphere(96));
  scene.materials.push_back({"Grey", "", testing::constantGraph("Grey", {0.5f, 0.5f, 0.5f}, 0.5f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  glm::mat4 sphere = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, kSphereHeight, 0.0f));
  scene.instances.push_back({1, 0, glm::scale(sphere, glm::vec3(kSphereRadius))});
  // The camera ray through the centre passes 0.45 below the sphere, the image's corners
  // 0.22 off that at most.
  scene.camera.position = {0.0f, 2.0f, 6.0f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 3.0f;
  return scene;
}

// The analytic unoccluded fraction at point p of the plane (infinite AO distance).
double analyticAmbientOcclusion(glm::dvec3 p) {
  const glm::dvec3 toCentre = glm::dvec3(0.0, kSphereHeight, 0.0) - p;
  const double d = glm::length(toCentre);
  const double cosTheta = toCentre.y / d;
  const double sinAlpha = kSphereRadius / d;
  return 1.0 - sinAlpha * sinAlpha * cosTheta;
}

// Where the ray through the centre of pixel (x, y) meets the plane, as primaryRay
// (path_shading.glsl) and the frame loop's camera basis make it.
glm::dvec3 planePointOfPixel(const Camera& camera, int x, int y, int width, int height) {
  const glm::dvec3 position(camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(glm::radians(double(camera.verticalFovDegrees)) * 0.5);
  const double aspect = double(width) / double(height);
  const double ndcX = (x + 0.5) / width * 2.0 - 1.0;
  const double ndcY = (y + 0.5) / height * 2.0 - 1.0;
  const glm::dvec3 direction =
      glm::normalize(forward + ndcX * tanHalf * aspect * right - ndcY * tanHalf * up);
  return position + (-position.y / direction.y) * direction;
}

RenderResult renderAmbientOcclusion(const Scene& scene, float distance, std::uint32_t samples,
                                    RenderSettings& settings, Backend backend = Backend::Auto,
                                    Shading shading = Shading::Auto) {
  RendererOptions options = testing::testOptions(backend);
  options.shading = shading;
  options.integrator = Integrator::AmbientOcclusion;
  options.ambientOcclusion.distance = distance;
  options.ambientOcclusion.samples = samples;
  Renderer renderer(options);
  settings.width = settings.height = 32;
  RenderResult result = renderer.render(scene, settings);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return result;
}

// Both trace backends: the GPU machine has only the ray-tracing pipeline's.
class AmbientOcclusionIntegratorBackend : public ::testing::TestWithParam<Backend> {};

TEST_P(AmbientOcclusionIntegratorBackend, PlaneUnderSphereMatchesTheAnalyticFraction) {
  const Scene scene = planeUnderSphere();
  RenderSettings settings;
  settings.pathsPerPixel = 8;
  settings.frames = 4;
  const std::uint32_t samples = 64;
  // Longer than any ray that can reach the sphere: the analytic case's infinite distance.
  const RenderResult result = renderAmbientOcclusion(scene, 100.0f, samples, settings, GetParam());
  ASSERT_EQ(result.stats.materialDispatch, "ao");

  // 2,048 rays a pixel: a pixel's fraction (about 0.8) spreads by sqrt(0.8 * 0.2 / 2048) =
  // 0.009; 0.05 is 5.5 of those. The image's mean error spreads by 0.0003 and carries the
  // tessellation's bias (the 96-segment sphere's silhouette is 0.05% smaller, the fraction
  // about 0.0002 larger): 0.004 leaves room for both and none for a wrong estimator.
  double sumError = 0.0, smallest = 1.0, largest = 0.0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const double expected =
          analyticAmbientOcclusion(planePointOfPixel(scene.camera, x, y, 32, 32));
      const double got = result.image.pixel(x, y)[0];
      EXPECT_NEAR(got, expected, 0.05) << "pixel " << x << "," << y;
      EXPECT_EQ(result.image.pixel(x, y)[0], result.image.pixel(x, y)[1]);
      sumError += got - expected;
      smallest = std::min(smallest, expected);
      largest = std::max(largest, expected);
    }
  }
  const double meanError = sumError / (32.0 * 32.0);
  std::printf("AO plane under sphere: analytic %.4f..%.4f, mean error %.5f\n", smallest, largest,
              meanError);
  EXPECT_NEAR(meanError, 0.0, 0.004);
  // Every primary ray hits the plane and every AO ray leaves above it: 1 + 64 rays a path.
  for (const FrameStats& frame : result.stats.frames)
    EXPECT_EQ(frame.rays, 32u * 32u * settings.pathsPerPixel * (1u + samples));
}

INSTANTIATE_TEST_SUITE_P(BothBackends, AmbientOcclusionIntegratorBackend,
                         ::testing::Values(Backend::RayQuery, Backend::RayTracingPipeline),
                         [](const auto& info) {
                           return std::string(info.param == Backend::RayQuery ? "query"
                                                                              : "pipeline");
                         });

TEST(AmbientOcclusionIntegrator, RaysShorterThanTheGapFindNothing) {
  const Scene scene = planeUnderSphere();
  RenderSettings settings;
  settings.pathsPerPixel = 2;
  // The sphere's lowest point is 0.5 above the plane: a 0.4 ray cannot reach it.
  const RenderResult result = renderAmbientOcclusion(scene, 0.4f, 16, settings);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      ASSERT_EQ(result.image.pixel(x, y)[0], 1.0f) << "pixel " << x << "," << y;
}

TEST(AmbientOcclusionIntegrator, DefaultDistanceIsATenthOfTheSceneDiagonal) {
  const Scene scene = planeUnderSphere();
  // The plane spans x, z in [-10, 10]; the sphere's box reaches y = 1.5.
  EXPECT_NEAR(defaultAmbientOcclusionDistance(scene), 0.1 * std::sqrt(400.0 + 400.0 + 2.25), 1e-4);
  EXPECT_FLOAT_EQ(resolveAmbientOcclusionDistance({2.0f, 16}, scene), 2.0f);
  EXPECT_FLOAT_EQ(defaultAmbientOcclusionDistance(Scene{}), 1.0f);
}

TEST(AmbientOcclusionIntegrator, RefusesWhatItCannotDo) {
  RendererOptions options;
  options.integrator = Integrator::AmbientOcclusion;
  options.cache.mode = CacheMode::Texel;
  EXPECT_THROW(validateIntegratorOptions(options), std::invalid_argument);
  options.cache.mode = CacheMode::None;
  options.culling.mode = CullingMode::Frustum;
  EXPECT_THROW(validateIntegratorOptions(options), std::invalid_argument);
  options.culling.mode = CullingMode::None;
  options.ambientOcclusion.samples = 0;
  EXPECT_THROW(validateIntegratorOptions(options), std::invalid_argument);
  options.ambientOcclusion.samples = 1;
  options.ambientOcclusion.distance = -1.0f;
  EXPECT_THROW(validateIntegratorOptions(options), std::invalid_argument);
  options.ambientOcclusion.distance = 0.0f;
  EXPECT_NO_THROW(validateIntegratorOptions(options));
  options.shading = Shading::Wavefront;
  EXPECT_NO_THROW(validateWavefrontOptions(options));
  // Auto keeps the megakernel, on a GPU too (the wavefront measured slower there).
  options.shading = Shading::Auto;
  EXPECT_EQ(resolveShading(options, {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true}).shading,
            Shading::Megakernel);
}

// The wavefront runs the AO integrator as rounds of generate, trace, an AO pass (the
// traced-inputs pass's slot) and finish, with the megakernel's estimator and random numbers
// (ambientOcclusionIntegratorAt): at one seed the same picture (exactly: a pixel is a count
// of unoccluded rays over the same rays) and the same rays, on both backends: 32x32, P = 2,
// 8 AO rays of length 1 (the sphere, 0.5 above the plane, occludes part of it).
TEST(AmbientOcclusionIntegrator, TheWavefrontGivesTheMegakernelsPictureAtOneSeed) {
  const Scene scene = planeUnderSphere();
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    SCOPED_TRACE(backend == Backend::RayQuery ? "query" : "pipeline");
    RenderSettings settings;
    settings.pathsPerPixel = 2;
    settings.seed = 7;
    const RenderResult megakernel =
        renderAmbientOcclusion(scene, 1.0f, 8, settings, backend, Shading::Megakernel);
    const RenderResult wavefront =
        renderAmbientOcclusion(scene, 1.0f, 8, settings, backend, Shading::Wavefront);
    EXPECT_EQ(megakernel.stats.shading, "megakernel");
    EXPECT_EQ(wavefront.stats.shading, "wavefront");
    ASSERT_EQ(megakernel.image.rgba.size(), wavefront.image.rgba.size());
    double largest = 0.0, mean = 0.0;
    for (std::size_t i = 0; i < megakernel.image.rgba.size(); ++i) {
      largest =
          std::max(largest, double(std::abs(megakernel.image.rgba[i] - wavefront.image.rgba[i])));
      mean += megakernel.image.rgba[i];
    }
    mean /= double(megakernel.image.rgba.size());
    std::printf(
        "AO integrator, wavefront against megakernel: largest difference %.3g (mean %.4f)\n",
        largest, mean);
    EXPECT_LT(largest, 1e-6);
    EXPECT_LT(mean, 0.99);  // the sphere occludes: not a picture of ones
    EXPECT_EQ(wavefront.stats.frames.back().rays, megakernel.stats.frames.back().rays);
    EXPECT_GT(wavefront.stats.frames.back().wavefrontTracedInputsMilliseconds, 0.0);
  }
}

}  // namespace
}  // namespace memograph::runtime
