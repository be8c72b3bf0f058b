// A Lambert-dominated plane under one point light: with one ray per path (direct light
// only) each pixel is f(wo, wi) * E, where E = I cos(theta) / d^2 is the analytic
// irradiance and f the thesis §2.1 BRDF evaluated here on the CPU. In both architectures.
#include <cmath>

#include <gtest/gtest.h>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

constexpr double kPi = 3.14159265358979;

// Eq. 2.2-2.7 with the renderer's dielectric split (96% Lambert, 4% Schlick F0).
double brdf(double albedo, double roughness, glm::dvec3 n, glm::dvec3 wo, glm::dvec3 wi) {
  double alpha = roughness * roughness;
  double a2 = alpha * alpha;
  glm::dvec3 h = glm::normalize(wo + wi);
  double ni = glm::dot(n, wi), no = glm::dot(n, wo), nh = glm::dot(n, h);
  double f = 0.04 + 0.96 * std::pow(1.0 - glm::dot(wi, h), 5.0);
  auto g1 = [&](double c) { return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c)); };
  double d = a2 / (kPi * std::pow(nh * nh * (a2 - 1) + 1, 2));
  return albedo * 0.96 / kPi + f * g1(ni) * g1(no) * d / (4 * ni * no);
}

class PointLight : public ::testing::TestWithParam<Shading> {};

TEST_P(PointLight, LambertPlaneMatchesAnalyticIrradiance) {
  const double albedo = 0.5, roughness = 1.0, intensity = 10.0;
  const glm::dvec3 light(0.3, 2.0, -0.2);
  Scene scene;
  scene.meshes.push_back(testing::quad(20.0f));
  scene.materials.push_back(
      {"Grey", "", testing::constantGraph("Grey", glm::vec3(float(albedo)), float(roughness))});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.lights.push_back({LightType::Point, glm::vec3(light), {0, -1, 0}, glm::vec3(intensity)});
  scene.camera.position = {0, 4, 2};
  scene.camera.target = {0, 0, 0};
  scene.camera.verticalFovDegrees = 40.0f;

  RendererOptions options = testing::testOptions();
  options.shading = GetParam();
  Renderer renderer(options);
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.raysPerPath = 1;
  settings.sharedPrimaryRay = true;  // rays through pixel centres, as the reference below
  RenderResult result = renderer.render(scene, settings);

  // setCamera's camera basis (trace/frame_loop.cpp), for the ray through each pixel centre.
  glm::dvec3 eye(scene.camera.position), forward = glm::normalize(-eye);
  glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  glm::dvec3 up = glm::cross(right, forward);
  double tanHalf = std::tan(20.0 * kPi / 180.0);
  double worst = 0;
  for (int y = 0; y < 32; y += 3) {
    for (int x = 0; x < 32; x += 3) {
      double nx = (x + 0.5) / 32 * 2 - 1, ny = (y + 0.5) / 32 * 2 - 1;
      glm::dvec3 d = glm::normalize(forward + nx * tanHalf * right - ny * tanHalf * up);
      double t = -eye.y / d.y;
      glm::dvec3 p = eye + t * d;
      glm::dvec3 toLight = light - p;
      double d2 = glm::dot(toLight, toLight);
      glm::dvec3 wi = toLight / std::sqrt(d2);
      glm::dvec3 n(0, 1, 0);
      double irradiance = intensity * wi.y / d2;  // E = I cos(theta) / d^2
      double expected = brdf(albedo, roughness, n, -d, wi) * irradiance;
      double got = result.image.pixel(x, y)[0];
      worst = std::max(worst, std::abs(got - expected) / expected);
      EXPECT_NEAR(got, expected, 0.01 * expected) << "pixel " << x << "," << y;
    }
  }
  std::printf("point light (%s): worst relative error %.5f\n", shadingName(GetParam()), worst);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

INSTANTIATE_TEST_SUITE_P(BothArchitectures, PointLight,
                         ::testing::Values(Shading::Megakernel, Shading::Wavefront),
                         [](const auto& info) { return std::string(shadingName(info.param)); });

}  // namespace
}  // namespace memograph::runtime
