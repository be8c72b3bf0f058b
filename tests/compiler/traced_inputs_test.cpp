// Traced inputs (compiler/traced_inputs.*, docs/design/traced-inputs.md): the Ambient
// Occlusion node reads a per-hit value the path tracer traces rays for before the graph runs.
// Its settings must be constants the metadata records, and the value must never land in the
// cached part of a graph (the cut): two hits of one texel see different occluders.
#include <gtest/gtest.h>

#include <string>

#include "compiler/variation.h"
#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::compileText;
using memograph::testing::realLibrary;

// The text of function `name` in `code`, from its signature to its closing brace.
std::string functionText(const std::string& code, const std::string& name) {
  const std::size_t start = code.find("void " + name + "(");
  if (start == std::string::npos)
    return {};
  return code.substr(start, code.find("\n}\n", start) + 3 - start);
}

// A UV noise whose colour the AO node darkens in creases: the noise is the cut, AO the rest.
constexpr const char* kUvNoiseUnderAmbientOcclusion =
    "material NoiseInCreases;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "AmbientOcclusion Color<2 Distance=0.25 Samples=8 Inside=1.0 Out>3 AO>4;\n"
    "BaseColorOutput In<3;\n"
    "RoughnessOutput In<4;\n";

TEST(TracedInputs, AmbientOcclusionIsPerHit) {
  EXPECT_EQ(inputVariation("ambientOcclusion"), Variation::PerHit);
}

TEST(TracedInputs, AmbientOcclusionNeverLandsInTheCut) {
  const auto run = compileText(kUvNoiseUnderAmbientOcclusion, realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  const CompiledMaterial& m = *run.material;
  EXPECT_FALSE(m.metadata.cacheable);
  EXPECT_EQ(m.metadata.cutDomain, "uv");
  const std::string cut = functionText(m.glsl, "EvaluateMaterialCut_NoiseInCreases");
  const std::string rest = functionText(m.glsl, "EvaluateMaterialRest_NoiseInCreases");
  ASSERT_FALSE(cut.empty()) << m.glsl;
  EXPECT_NE(cut.find("NoiseTexture"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("AmbientOcclusion"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("ambientOcclusion"), std::string::npos) << cut;
  EXPECT_NE(rest.find("AmbientOcclusion("), std::string::npos) << rest;
  EXPECT_EQ(rest.find("NoiseTexture"), std::string::npos) << rest;
  // Both targets compile the node (written once for GLSL and HLSL).
  const auto glsl = memograph::testing::compileGlslMaterials({m.glsl}, {"NoiseInCreases"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  const auto hlsl = memograph::testing::compileHlslMaterials({m.hlsl}, {"NoiseInCreases"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
}

TEST(TracedInputs, AnAmbientOcclusionFeedingANoiseLeavesNothingToCache) {
  const auto run = compileText(
      "material CreaseNoise;\n"
      "UVInput Out>1;\n"
      "AmbientOcclusion AO>2;\n"
      "Add A<1 B<2 Out>3;\n"
      "NoiseTexture Vector<3 Detail=2.0 Color>4;\n"
      "BaseColorOutput In<4;\n",
      realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  EXPECT_EQ(run.material->metadata.cutDomain, "none");
}

TEST(TracedInputs, MetadataRecordsTheSettings) {
  const auto run = compileText(kUvNoiseUnderAmbientOcclusion, realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  const auto& ao = run.material->metadata.ambientOcclusion;
  ASSERT_TRUE(ao.has_value());
  EXPECT_DOUBLE_EQ(ao->distance, 0.25);
  EXPECT_EQ(ao->samples, 8u);
  EXPECT_TRUE(ao->inside);
  EXPECT_FALSE(ao->onlyLocal);
  EXPECT_NE(run.material->metadataJson.find(
                "\"ambientOcclusion\": {\"distance\": 0.25, \"samples\": 8, \"inside\": true, "
                "\"onlyLocal\": false}"),
            std::string::npos)
      << run.material->metadataJson;
  const auto& inputs = run.material->metadata.inputsUsed;
  EXPECT_NE(std::find(inputs.begin(), inputs.end(), "ambientOcclusion"), inputs.end());
}

TEST(TracedInputs, DefaultsAreBlendersAndGraphsWithoutAoRecordNone) {
  const auto run = compileText(
      "material PlainAo;\nAmbientOcclusion Out>1;\nBaseColorOutput In<1;\n", realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  ASSERT_TRUE(run.material->metadata.ambientOcclusion.has_value());
  EXPECT_EQ(*run.material->metadata.ambientOcclusion, AmbientOcclusionSettings{});
  const auto plain =
      compileText("material Plain;\nBaseColorOutput In=(1.0, 0.0, 0.0);\n", realLibrary());
  ASSERT_TRUE(plain.material) << plain.messages();
  EXPECT_FALSE(plain.material->metadata.ambientOcclusion.has_value());
  EXPECT_EQ(plain.material->metadataJson.find("ambientOcclusion"), std::string::npos);
}

TEST(TracedInputs, ALinkedSettingIsAnError) {
  const auto run = compileText(
      "material LinkedDistance;\n"
      "UVInput Out>1;\n"
      "SeparateXYZ Vector<1 X>2;\n"
      "AmbientOcclusion Distance<2 Out>3;\n"
      "BaseColorOutput In<3;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("AmbientOcclusion.Distance must be a constant"), std::string::npos)
      << run.messages();
}

TEST(TracedInputs, TwoAoNodesMustAgree) {
  const auto run = compileText(
      "material TwoAo;\n"
      "AmbientOcclusion Distance=1.0 AO>1;\n"
      "AmbientOcclusion Distance=2.0 AO>2;\n"
      "Add A<1 B<2 Out>3;\n"
      "RoughnessOutput In<3;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("different settings"), std::string::npos) << run.messages();
}

TEST(TracedInputs, SamplesOutOfRangeIsAnError) {
  const auto run = compileText(
      "material ManySamples;\nAmbientOcclusion Samples=500 AO>1;\nRoughnessOutput In<1;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("Samples must be a whole number from 1 to 128"), std::string::npos)
      << run.messages();
}

// A UV noise colours the surface and Bevel rounds its edges: the noise is the cut, Bevel the
// rest.
constexpr const char* kUvNoiseWithBevel =
    "material RoundedNoise;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "Bevel Radius=0.1 Samples=8 Normal>3;\n"
    "BaseColorOutput In<2;\n"
    "NormalOutput In<3;\n";

TEST(TracedInputs, BevelIsPerHitAndNeverInTheCut) {
  EXPECT_EQ(inputVariation("bevelNormal"), Variation::PerHit);
  const auto run = compileText(kUvNoiseWithBevel, realLibrary());
  ASSERT_TRUE(run.material) << run.messages();
  const CompiledMaterial& m = *run.material;
  EXPECT_EQ(m.metadata.cutDomain, "uv");
  const std::string cut = functionText(m.glsl, "EvaluateMaterialCut_RoundedNoise");
  const std::string rest = functionText(m.glsl, "EvaluateMaterialRest_RoundedNoise");
  EXPECT_NE(cut.find("NoiseTexture"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("Bevel"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("bevelNormal"), std::string::npos) << cut;
  EXPECT_NE(rest.find("Bevel("), std::string::npos) << rest;
  const auto& bevel = m.metadata.bevel;
  ASSERT_TRUE(bevel.has_value());
  EXPECT_DOUBLE_EQ(bevel->radius, 0.1);
  EXPECT_EQ(bevel->samples, 8u);
  EXPECT_FALSE(m.metadata.ambientOcclusion.has_value());
  EXPECT_NE(m.metadataJson.find("\"bevel\": {\"radius\": 0.1, \"samples\": 8}"), std::string::npos)
      << m.metadataJson;
  const auto glsl = memograph::testing::compileGlslMaterials({m.glsl}, {"RoundedNoise"});
  EXPECT_TRUE(glsl.ok) << glsl.log;
  const auto hlsl = memograph::testing::compileHlslMaterials({m.hlsl}, {"RoundedNoise"});
  EXPECT_TRUE(hlsl.ok) << hlsl.log;
}

TEST(TracedInputs, ALinkedBevelRadiusIsAnError) {
  const auto run = compileText(
      "material LinkedRadius;\n"
      "UVInput Out>1;\n"
      "SeparateXYZ Vector<1 X>2;\n"
      "Bevel Radius<2 Normal>3;\n"
      "NormalOutput In<3;\n",
      realLibrary());
  EXPECT_FALSE(run.material);
  EXPECT_NE(run.messages().find("Bevel.Radius must be a constant"), std::string::npos)
      << run.messages();
}

}  // namespace
}  // namespace memograph::compiler
