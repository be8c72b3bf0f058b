// The transmission lobes' geometry and Fresnel (runtime/shaders/common/bsdf_lobes.glsl,
// brdf.glsl fresnelDielectric) against closed forms: a compute shader calls the functions the
// path tracer calls and writes what they return; the values are checked here. Snell's law
// sin(theta_t) = sin(theta_i) / eta, the unpolarised Fresnel reflectance
// 1/2 (r_s^2 + r_p^2), total internal reflection past the critical angle, the sharp Glass
// lobe's Fresnel choice, and the rough Refraction lobe's f |cos| / pdf: G1(i) for GGX's
// visible normals (its evaluation and density agree, as in Cycles'
// bsdf_microfacet_ggx_eval_transmit), Walter et al.'s weight for Beckmann's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "render_test_support.h"
#include "runtime/vk/compute_pipeline.h"
#include "runtime/vk/gpu_buffer.h"
#include "runtime/vk/shader_compiler.h"
#include "runtime/vk/shader_sources.h"

namespace memograph::runtime {
namespace {

constexpr const char* kShader = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
layout(local_size_x = 1) in;
layout(buffer_reference, std430) buffer Results { float values[]; };
layout(push_constant) uniform Push { Results results; } push;

// What bsdf_lobes.glsl needs of the node library's prelude (nodes/prelude/common.inc).
#define MG_BSDF_LOBES 1
#define MG_MAX_LOBES 4
#define MG_LOBE_DIFFUSE 1
#define MG_LOBE_GLOSSY_GGX 2
#define MG_LOBE_GLOSSY_BECKMANN 3
#define MG_LOBE_VELVET 4
#define MG_LOBE_TRANSLUCENT 5
#define MG_LOBE_TRANSPARENT 6
#define MG_LOBE_REFRACTION_GGX 7
#define MG_LOBE_REFRACTION_BECKMANN 8
#define MG_LOBE_GLASS_GGX 9
#define MG_LOBE_GLASS_BECKMANN 10
#define MG_LOBE_PRINCIPLED 11
#define MG_LOBE_PRINCIPLED_SHEEN 12
#define MG_LOBE_PRINCIPLED_CLEARCOAT 13
#define MG_LOBE_PRINCIPLED_GLASS 14
struct MaterialOutputs {
  vec3 baseColor;
  float roughness;
  float specularTint;
  int lobeCount;
  vec4 lobeWeight[MG_MAX_LOBES];
  vec4 lobeParameters[MG_MAX_LOBES];
};
#include "brdf.glsl"
#include "bsdf_lobes.glsl"

void put(inout uint n, vec3 v) {
  push.results.values[n] = v.x; push.results.values[n + 1u] = v.y;
  push.results.values[n + 2u] = v.z; n += 3u;
}
void put(inout uint n, float v) { push.results.values[n] = v; n += 1u; }

void main() {
  uint n = 0u;
  float s45 = sqrt(0.5);
  vec3 wo45 = vec3(s45, 0.0, s45);
  vec3 wo30 = vec3(0.5, 0.0, sqrt(0.75));
  put(n, fresnelDielectric(1.0, 1.5));                           // 0
  put(n, fresnelDielectric(s45, 1.5));                           // 1
  put(n, fresnelDielectric(sqrt(0.75), 1.0 / 1.5));              // 2
  put(n, fresnelDielectric(0.5, 1.0 / 1.5));                     // 3: past the critical angle
  put(n, refractDirection(wo45, vec3(0.0, 0.0, 1.0), 1.5));      // 4..6
  put(n, refractDirection(vec3(sqrt(0.75), 0.0, 0.5), vec3(0.0, 0.0, 1.0), 1.0 / 1.5));  // 7..9
  float w;
  // The sharp Glass lobe: reflection below uChoice = F (0.0502 at 45 degrees), else refraction.
  put(n, lobeSample(MG_LOBE_GLASS_GGX, 0.0, 1.5, wo45, vec2(0.5), 0.04, w));  // 10..12
  put(n, lobeSample(MG_LOBE_GLASS_GGX, 0.0, 1.5, wo45, vec2(0.5), 0.06, w));  // 13..15
  put(n, w);                                                                 // 16
  put(n, lobeSample(MG_LOBE_TRANSPARENT, 0.0, 0.0, wo30, vec2(0.5), 0.5, w));  // 17..19
  // A singular lobe has no density and no value at any direction.
  put(n, lobeEvaluateCos(MG_LOBE_GLASS_GGX, 0.0, 1.5, wo45, vec3(-0.4714, 0.0, -0.8819)));  // 20
  // Rough refraction (GGX, alpha 0.25): f |cos| / pdf at a sampled direction is G1(i).
  vec3 wi = lobeSample(MG_LOBE_REFRACTION_GGX, 0.5, 1.5, wo30, vec2(0.3, 0.7), 0.5, w);
  put(n, lobeEvaluateCos(MG_LOBE_REFRACTION_GGX, 0.5, 1.5, wo30, wi) /
             lobePdf(MG_LOBE_REFRACTION_GGX, 0.5, 1.5, wo30, wi));  // 21
  put(n, smithG1(wi.z, 0.25));                                      // 22
  put(n, wi.z);                                                     // 23: through the surface
  // Leaving the denser side (eta 1 / 1.5), Beckmann.
  wi = lobeSample(MG_LOBE_REFRACTION_BECKMANN, 0.5, 1.0 / 1.5, wo30, vec2(0.6, 0.2), 0.5, w);
  put(n, lobeEvaluateCos(MG_LOBE_REFRACTION_BECKMANN, 0.5, 1.0 / 1.5, wo30, wi) /
             lobePdf(MG_LOBE_REFRACTION_BECKMANN, 0.5, 1.0 / 1.5, wo30, wi));  // 24
  // Beckmann's normals are drawn by D(h) n.h, not the visible ones: f |cos| / pdf is
  // G1(o) G1(i) o.h / (n.o n.h) (Walter et al. 2007, eq. 41).
  vec3 h;
  refractionHalfVector(wo30, wi, 1.0 / 1.5, h);
  put(n, beckmannG1(wo30.z, 0.25) * beckmannG1(wi.z, 0.25) * dot(wo30, h) / (wo30.z * h.z));
  // Translucent: cosine-weighted on the far side.
  wi = lobeSample(MG_LOBE_TRANSLUCENT, 0.0, 0.0, wo30, vec2(0.36, 0.25), 0.5, w);
  put(n, wi);                                                                         // 26..28
  put(n, lobeEvaluateCos(MG_LOBE_TRANSLUCENT, 0.0, 0.0, wo30, wi));                  // 29
  put(n, lobeEvaluateCos(MG_LOBE_TRANSLUCENT, 0.0, 0.0, wo30, vec3(0.0, 0.0, 1.0)));  // 30
}
)";

constexpr int kResults = 31;

std::vector<float> runLobeFunctions() {
  Renderer renderer(testing::testOptions());
  const VulkanContext& context = renderer.context();
  ShaderCompiler compiler =
      ShaderCompiler(embeddedShaderFiles(), {}).withFile("bsdf_transmission_test.comp", kShader);
  auto module = createShaderModule(
      context.device(),
      compiler.compile({"bsdf_transmission_test.comp", ShaderStage::Compute, {}}));
  auto layout = createPipelineLayout(context.device(), VK_NULL_HANDLE, VK_SHADER_STAGE_COMPUTE_BIT,
                                     sizeof(VkDeviceAddress));
  auto pipeline =
      createComputePipeline(context, module.get(), layout.get(), "bsdf transmission test");
  GpuBuffer results =
      hostBuffer(context, kResults * sizeof(float),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  VkDeviceAddress address = results.address();
  context.submitAndWait([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdPushConstants(commands, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(address),
                       &address);
    vkCmdDispatch(commands, 1, 1, 1);
  });
  std::vector<float> values(kResults);
  results.read(values.data(), values.size() * sizeof(float));
  EXPECT_TRUE(renderer.context().validationErrors().empty());
  return values;
}

TEST(BsdfTransmission, RefractionAndFresnelMatchClosedForms) {
  std::vector<float> v = runLobeFunctions();
  // Fresnel: ((eta - 1) / (eta + 1))^2 = 0.04 head-on; 1/2 (r_s^2 + r_p^2) at 45 degrees into
  // glass (0.050240) and at 30 degrees out of it (0.055190); 1 past the critical angle
  // asin(1 / 1.5) = 41.8 degrees. Float arithmetic: within 1e-5.
  EXPECT_NEAR(v[0], 0.04, 1e-5);
  EXPECT_NEAR(v[1], 0.0502399, 1e-5);
  EXPECT_NEAR(v[2], 0.0551902, 1e-5);
  EXPECT_EQ(v[3], 1.0f);
  // Snell: 45 degrees into glass leaves at sin = 0.7071 / 1.5 = 0.471405, on the far side and
  // away from wo's tangent direction; 60 degrees out of glass is past the critical angle.
  EXPECT_NEAR(v[4], -0.471405, 1e-5);
  EXPECT_NEAR(v[5], 0.0, 1e-6);
  EXPECT_NEAR(v[6], -0.881917, 1e-5);
  EXPECT_EQ(v[7], 0.0f);
  EXPECT_EQ(v[8], 0.0f);
  EXPECT_EQ(v[9], 0.0f);
  // Sharp glass: the mirror direction below F, the refracted one above, each of weight 1.
  EXPECT_NEAR(v[10], -0.707107, 1e-5);
  EXPECT_NEAR(v[12], 0.707107, 1e-5);
  EXPECT_NEAR(v[13], -0.471405, 1e-5);
  EXPECT_NEAR(v[15], -0.881917, 1e-5);
  EXPECT_EQ(v[16], 1.0f);
  // Transparent: straight on, wi = -wo.
  EXPECT_NEAR(v[17], -0.5, 1e-6);
  EXPECT_NEAR(v[19], -0.866025, 1e-5);
  EXPECT_EQ(v[20], 0.0f);
  // Rough refraction: evaluation over density is the sampling weight above, within float
  // error (1e-4 relative).
  EXPECT_LT(v[23], 0.0f);
  EXPECT_NEAR(v[21], v[22], 1e-4 * v[22]);
  EXPECT_NEAR(v[24], v[25], 1e-4 * v[25]);
  // Translucent: u = (0.36, 0.25) gives r = 0.6 at phi = 90 degrees, z = -0.8; its value is
  // |cos| / pi, and nothing on the near side.
  EXPECT_NEAR(v[26], 0.0, 1e-6);
  EXPECT_NEAR(v[27], 0.6, 1e-6);
  EXPECT_NEAR(v[28], -0.8, 1e-6);
  EXPECT_NEAR(v[29], 0.8 / M_PI, 1e-6);
  EXPECT_EQ(v[30], 0.0f);
}

}  // namespace
}  // namespace memograph::runtime
