#include "glslang_check.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <mutex>

namespace memograph::testing {

namespace {

void initializeOnce() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

ShaderCheck compile(const std::string& source, glslang::EShSource language) {
  initializeOnce();
  glslang::TShader shader(EShLangCompute);
  const char* text = source.c_str();
  shader.setStrings(&text, 1);
  shader.setEntryPoint("main");
  shader.setSourceEntryPoint("main");
  shader.setEnvInput(language, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  const auto messages = static_cast<EShMessages>(
      EShMsgSpvRules | EShMsgVulkanRules |
      (language == glslang::EShSourceHlsl ? EShMsgReadHlsl : EShMsgDefault));
  ShaderCheck result;
  if (!shader.parse(GetDefaultResources(), 460, false, messages)) {
    result.log = shader.getInfoLog();
    return result;
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    result.log = program.getInfoLog();
    return result;
  }
  std::vector<unsigned int> spirv;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &logger);
  result.log = logger.getAllMessages();
  result.ok = !spirv.empty();
  return result;
}

// Both targets' main functions: the texture stub the generated code calls, and the inputs
// (with derivatives where they carry them) from the invocation's id, in the generated code's
// portable types.
constexpr const char* kSampleTexture = R"(
float4 mg_SampleTexture(int textureIndex, float2 uv, float2 ddx, float2 ddy) {
  return float4(uv, ddx.x + ddy.y, float(textureIndex));
}
)";
const std::string kFillInputs = R"(  MaterialInputs inputs;
  inputs.uv = mg_make_float2_D(float2(id.xy), float2(1.0, 0.0), float2(0.0, 1.0));
  inputs.position = mg_make_float3_D(float3(id), float3(1.0, 0.0, 0.0), float3(0.0, 1.0, 0.0));
  inputs.normal = float3(0.0, 0.0, 1.0);
  inputs.tangent = float3(1.0, 0.0, 0.0);
  inputs.bitangentSign = float3(1.0, 0.0, 0.0);
  inputs.vertexColor = float4(1.0, 1.0, 1.0, 1.0);
  inputs.view = float3(0.0, 0.0, 1.0);
  inputs.time = 0.5;
  inputs.textureBase = 0;
  MaterialOutputs outputs;
)";

// Writes every output so nothing is optimised away before the checks run.
std::string callAll(const std::vector<std::string>& names) {
  std::string body;
  for (const auto& name : names) {
    body += "  EvaluateMaterial_" + name + "(inputs, outputs);\n";
    body +=
        "  result[0] += float4(outputs.baseColor + outputs.normal + outputs.emission, "
        "outputs.metallic + outputs.roughness + outputs.opacity);\n";
  }
  return body;
}

}  // namespace

ShaderCheck compileGlslMaterials(const std::vector<std::string>& includes,
                                 const std::vector<std::string>& names) {
  std::string source = "#version 460\n";
  for (const auto& include : includes)
    source += include;
  source += kSampleTexture;
  source += R"(layout(local_size_x = 8) in;
layout(std430, set = 0, binding = 0) buffer Result { float4 result[]; };
void main() {
  uvec3 id = gl_GlobalInvocationID;
)";
  source += kFillInputs + callAll(names) + "}\n";
  return compile(source, glslang::EShSourceGlsl);
}

ShaderCheck compileHlslMaterials(const std::vector<std::string>& includes,
                                 const std::vector<std::string>& names) {
  std::string source;
  for (const auto& include : includes)
    source += include;
  source += kSampleTexture;
  source += R"(RWStructuredBuffer<float4> result : register(u0);
[numthreads(8, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
)";
  source += kFillInputs + callAll(names) + "}\n";
  return compile(source, glslang::EShSourceHlsl);
}

ShaderCheck compileGlslCode(const std::string& code) {
  return compile("#version 460\n" + code + "\nlayout(local_size_x = 1) in;\nvoid main() {}\n",
                 glslang::EShSourceGlsl);
}

ShaderCheck compileHlslCode(const std::string& code) {
  return compile(code + "\n[numthreads(1, 1, 1)]\nvoid main() {}\n", glslang::EShSourceHlsl);
}

}  // namespace memograph::testing
