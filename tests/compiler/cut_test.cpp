// Variation analysis and the cut (compiler/variation.*, compiler/cut.*): graphs built to have
// known cuts, the emitted cut and rest functions (glslang, SSA, golden files) and the
// metadata that reports them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "compiler/cut.h"
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

struct Compiled {
  MaterialMetadata metadata;
  std::string glsl;
  std::string hlsl;
  std::string cut;   // EvaluateMaterialCut_<Name>'s GLSL
  std::string rest;  // EvaluateMaterialRest_<Name>'s GLSL
};

Compiled compileReal(const std::string& graph) {
  const auto run = compileText(graph, realLibrary());
  EXPECT_TRUE(run.material) << run.messages();
  if (!run.material)
    return {};
  const auto& m = *run.material;
  return {m.metadata, m.glsl, m.hlsl,
          functionText(m.glsl, "EvaluateMaterialCut_" + m.metadata.name),
          functionText(m.glsl, "EvaluateMaterialRest_" + m.metadata.name)};
}

// A UV noise (five octaves) whose colour a Layer Weight mixes towards white: the noise is the
// cut, the view-dependent mix the rest.
constexpr const char* kUvPrefixViewTail =
    "material UvTail;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=4.0 Fac>2 Color>3;\n"
    "LayerWeight Blend=0.3 Facing>4;\n"
    "Mix A<3 B=(1.0, 1.0, 1.0) Factor<4 Out>5;\n"
    "BaseColorOutput In<5;\n"
    "RoughnessOutput In<2;\n";

constexpr const char* kGeneratedUnderLayerWeight =
    "material GeneratedUnderLayerWeight;\n"
    "TextureCoordinate Generated>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "LayerWeight Facing>3;\n"
    "MixColor Factor<3 A<2 B=(0.0, 0.0, 0.0) Result>4;\n"
    "BaseColorOutput In<4;\n";

// A UV noise whose colour Light Path switches: white for camera rays, the noise for the
// others, and darker with every bounce (Ray Depth). The noise is the cut; Light Path, per ray,
// stays in the rest.
constexpr const char* kUvNoiseUnderLightPath =
    "material RaySwitched;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "LightPath IsCameraRay>3 RayDepth>4;\n"
    "Mix A<2 B=(1.0, 1.0, 1.0) Factor<3 Out>5;\n"
    "Add A<4 B=1.0 Out>6;\n"
    "Div A=1.0 B<6 Out>7;\n"
    "BaseColorOutput In<5;\n"
    "RoughnessOutput In<7;\n";

TEST(Variation, KeyDomainsMixToPerHitAndTimeToPerFrame) {
  EXPECT_EQ(join(Variation::Constant, Variation::Uv), Variation::Uv);
  EXPECT_EQ(join(Variation::Object, Variation::Object), Variation::Object);
  EXPECT_EQ(join(Variation::Uv, Variation::Object), Variation::PerHit);
  EXPECT_EQ(join(Variation::World, Variation::Uv), Variation::PerHit);
  EXPECT_EQ(join(Variation::PerHit, Variation::Object), Variation::PerHit);
  EXPECT_EQ(join(Variation::Uv, Variation::PerFrame), Variation::PerFrame);
  EXPECT_EQ(join(Variation::PerHit, Variation::PerFrame), Variation::PerFrame);
}

TEST(Variation, EveryMaterialInputHasItsClass) {
  EXPECT_EQ(inputVariation("uv"), Variation::Uv);
  EXPECT_EQ(inputVariation("generated"), Variation::Object);
  EXPECT_EQ(inputVariation("objectPosition"), Variation::Object);
  // Per instance: constant over an instance, and the object-space key names the instance.
  EXPECT_EQ(inputVariation("objectRandom"), Variation::Object);
  EXPECT_EQ(inputVariation("objectLocation"), Variation::Object);
  EXPECT_EQ(inputVariation("position"), Variation::World);
  EXPECT_EQ(inputVariation("time"), Variation::PerFrame);
  for (const char* perHit :
       {"normal", "tangent", "vertexColor", "view", "geometricNormal", "backfacing"})
    EXPECT_EQ(inputVariation(perHit), Variation::PerHit) << perHit;
  // The path state (Light Path) is the ray's: never a key domain, so never in a cut.
  for (const char* perRay :
       {"rayFlags", "rayLength", "rayDepth", "diffuseDepth", "glossyDepth", "transmissionDepth"})
    EXPECT_EQ(inputVariation(perRay), Variation::PerHit) << perRay;
}

// The per-socket table names nodes and sockets of the real library, and covers every source
// node whose outputs copy members of different classes (else such a node's key-domain output
// would be classed by its per-hit siblings, and its cut lost).
TEST(Variation, SourceSocketTableMatchesTheLibrary) {
  for (const auto& entry : sourceSocketClasses()) {
    const NodeType* type = realLibrary().find(entry.node);
    ASSERT_NE(type, nullptr) << entry.node;
    EXPECT_GE(type->socketIndex(entry.socket), 0) << entry.node << "." << entry.socket;
  }
  for (const auto& type : realLibrary().nodeTypes()) {
    bool hasInputSocket = false;
    std::size_t outputs = 0;
    for (const auto& socket : type.sockets) {
      hasInputSocket = hasInputSocket || socket.direction == Direction::In;
      outputs += socket.direction != Direction::In;
    }
    std::set<Variation> classes;
    for (const auto& member : type.inputsRead)
      classes.insert(inputVariation(member));
    if (hasInputSocket || outputs < 2 || classes.size() < 2)
      continue;
    for (const auto& socket : type.sockets) {
      const bool listed = std::any_of(
          sourceSocketClasses().begin(), sourceSocketClasses().end(),
          [&](const auto& e) { return e.node == type.name && e.socket == socket.name; });
      EXPECT_TRUE(listed) << type.name << "." << socket.name << " has no class in the table";
    }
  }
}

// The cost table names only library nodes (a misspelt row would leave its node at the
// default cost 1), and every node outside the one-operation families (arithmetic,
// conversions, vectors) has a row: a texture, ramp or colour node at cost 1 would make the
// cut's cached share and its choice of domain wrong without a sign.
TEST(Cut, TheCostTableCoversEveryNodeWithMoreThanOneOperation) {
  const std::set<std::string> oneOperationFamilies = {
      "math.inc", "blender_math.inc", "converter.inc", "blender_conversions.inc", "vector.inc"};
  std::set<std::string> estimated;
  for (const auto name : nodesWithCostEstimates()) {
    EXPECT_NE(realLibrary().find(name), nullptr)
        << name << " is in the cost table, not the library";
    EXPECT_TRUE(estimated.insert(std::string(name)).second) << name << " has two rows";
  }
  for (const auto& type : realLibrary().nodeTypes()) {
    const std::string family = std::filesystem::path(type.file).filename().string();
    if (oneOperationFamilies.count(family) == 0) {
      EXPECT_EQ(estimated.count(type.name), 1u)
          << type.name << " (" << family << ") has no row in compiler/cut.cpp's kNodeCosts";
    }
  }
}

TEST(Cut, UvPrefixWithAViewDependentTailCachesTheNoise) {
  const auto c = compileReal(kUvPrefixViewTail);
  EXPECT_FALSE(c.metadata.cacheable);  // the whole-graph meaning is unchanged
  EXPECT_EQ(c.metadata.cutDomain, "uv");
  EXPECT_EQ(c.metadata.cutWidth, 4u);  // the noise's Fac (1) and Color (3)
  // The calibrated costs (compiler/cut.cpp): Noise 0.5 + 276.8 per octave, 5 octaves; Layer
  // Weight 18.4, Mix 1.
  EXPECT_NEAR(c.metadata.cutCostShare, 1384.5 / (1384.5 + 18.4 + 1.0), 1e-9);
  EXPECT_NE(c.cut.find("NoiseTexture"), std::string::npos) << c.cut;
  EXPECT_EQ(c.cut.find("LayerWeight"), std::string::npos) << c.cut;
  EXPECT_EQ(c.rest.find("NoiseTexture"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("LayerWeight"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("Mix("), std::string::npos) << c.rest;
}

TEST(Cut, GeneratedNoiseUnderALayerWeightMixIsAnObjectSpaceCut) {
  const auto c = compileReal(kGeneratedUnderLayerWeight);
  EXPECT_EQ(c.metadata.cutDomain, "object");
  EXPECT_EQ(c.metadata.cutWidth, 3u);
  // Noise 0.5 + 276.8 * 3 octaves = 830.9; Layer Weight 18.4, MixColor 5.9.
  EXPECT_NEAR(c.metadata.cutCostShare, 830.9 / (830.9 + 18.4 + 5.9), 1e-9);
  EXPECT_NE(c.cut.find("TextureCoordinate"), std::string::npos);
  EXPECT_EQ(c.rest.find("TextureCoordinate"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("MixColor"), std::string::npos);
}

// A Generated-coordinate noise height under a Bump (Blender's usual bump).
constexpr const char* kBumpOverGeneratedNoise =
    "material BumpOverNoise;\n"
    "TextureCoordinate Generated>1;\n"
    "NoiseTexture Vector<1 Detail=3.0 Fac>2;\n"
    "Bump Height<2 Normal>3;\n"
    "NormalOutput In<3;\n";

// A uv noise height under a Bump: a 2D key space, one run.
constexpr const char* kBumpOverUvNoise =
    "material BumpOverUvNoise;\n"
    "UVInput Out>1;\n"
    "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
    "Bump Height<2 Normal>3;\n"
    "NormalOutput In<3;\n"
    "RoughnessOutput In=0.4;\n";

// Bump reads its height's derivatives along the hit's own footprint axes; the cut carries the
// height with its gradient along object space's x, y and z (cut.h), so the noise, evaluated
// with derivatives at three points, is cached, and the rest rebuilds the hit's derivatives from
// its own object-space footprint.
TEST(Cut, BumpOverANoiseHeightCachesTheHeightWithItsGradient) {
  const auto c = compileReal(kBumpOverGeneratedNoise);
  EXPECT_TRUE(c.metadata.needsDerivatives);
  EXPECT_EQ(c.metadata.cutDomain, "object");
  EXPECT_EQ(c.metadata.cutWidth, 4u);  // the height and its gradient's three components
  // The noise's derivative overload: (0.5 + 276.8 * 4 octaves) * 3 = 3323.1; Bump 12.
  EXPECT_NEAR(c.metadata.cutCostShare, 3323.1 / (3323.1 + 12.0), 1e-9);
  EXPECT_NE(c.cut.find("NoiseTexture"), std::string::npos) << c.cut;
  EXPECT_EQ(c.rest.find("NoiseTexture"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("Bump("), std::string::npos) << c.rest;
  // Two runs: x and y, then z, one key step long; the gradient per unit of the step.
  EXPECT_NE(c.cut.find("for (int axisRun = 0; axisRun < 2; ++axisRun)"), std::string::npos)
      << c.cut;
  EXPECT_NE(c.cut.find("inputs.generated.x = inputs.objectPosition.x * inputs.generatedScale;"),
            std::string::npos)
      << c.cut;
  EXPECT_NE(c.cut.find("cut.v[3] = link2.x / keyStep;"), std::string::npos) << c.cut;
  // The chain rule along the hit's footprint: d/dx = grad . d(objectPosition)/dx.
  EXPECT_NE(c.rest.find("cut.v[1] * inputs.objectPosition.x.x + cut.v[2] * "
                        "inputs.objectPosition.x.y + cut.v[3] * inputs.objectPosition.x.z"),
            std::string::npos)
      << c.rest;
}

// In uv space the gradient has two axes, and one run of the part gives both.
TEST(Cut, BumpOverAUvNoiseCachesItsUvGradientInOneRun) {
  const auto c = compileReal(kBumpOverUvNoise);
  EXPECT_EQ(c.metadata.cutDomain, "uv");
  EXPECT_EQ(c.metadata.cutWidth, 9u);  // a colour and its two gradient vectors
  EXPECT_EQ(c.cut.find("axisRun"), std::string::npos) << c.cut;
  EXPECT_NE(c.cut.find("inputs.uv.x = float2(keyStep, 0.0);"), std::string::npos) << c.cut;
  EXPECT_NE(c.rest.find("float3(cut.v[3], cut.v[4], cut.v[5]) * inputs.uv.x.x + "
                        "float3(cut.v[6], cut.v[7], cut.v[8]) * inputs.uv.x.y"),
            std::string::npos)
      << c.rest;
}

// A plain branch beside the Bump caches in the same entry, without a gradient.
TEST(Cut, BumpBesideAPlainBranchCachesBoth) {
  const auto c = compileReal(
      "material BumpBesideColor;\n"
      "TextureCoordinate Generated>1;\n"
      "NoiseTexture Vector<1 Detail=3.0 Fac>2;\n"
      "Bump Height<2 Normal>3;\n"
      "NormalOutput In<3;\n"
      "VoronoiTexture Vector<1 Color>4;\n"
      "BaseColorOutput In<4;\n");
  EXPECT_EQ(c.metadata.cutDomain, "object");
  EXPECT_EQ(c.metadata.cutWidth, 7u);
  EXPECT_NE(c.cut.find("VoronoiTexture"), std::string::npos) << c.cut;
  EXPECT_NE(c.cut.find("NoiseTexture"), std::string::npos) << c.cut;
  EXPECT_EQ(c.rest.find("NoiseTexture"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("Bump("), std::string::npos) << c.rest;
}

TEST(Cut, AViewDependentGraphHasNoCut) {
  const auto c = compileReal(
      "material ViewOnly;\n"
      "LayerWeight Facing>1;\n"
      "NoiseTexture Vector<1 Detail=2.0 Color>2;\n"
      "BaseColorOutput In<2;\n");
  EXPECT_EQ(c.metadata.cutDomain, "none");
  EXPECT_TRUE(c.cut.empty());
  EXPECT_TRUE(c.rest.empty());
}

// uv and object space together have no single key: the noise of their sum is per hit.
TEST(Cut, MixingUvAndObjectSpaceIsPerHit) {
  const auto c = compileReal(
      "material UvAndObject;\n"
      "UVInput Out>1;\n"
      "TextureCoordinate Object>2;\n"
      "Add A<1 B<2 Out>3;\n"
      "NoiseTexture Vector<3 Detail=2.0 Color>4;\n"
      "BaseColorOutput In<4;\n");
  EXPECT_EQ(c.metadata.cutDomain, "none");
}

TEST(Cut, TimeMakesAValuePerFrame) {
  const auto c = compileReal(
      "material Scrolling;\n"
      "UVInput Out>1;\n"
      "TimeInput Out>2;\n"
      "Add A<1 B<2 Out>3;\n"
      "NoiseTexture Vector<3 Detail=2.0 Color>4;\n"
      "BaseColorOutput In<4;\n");
  EXPECT_EQ(c.metadata.cutDomain, "none");
}

TEST(Cut, LightPathStaysOutOfTheCut) {
  const auto c = compileReal(kUvNoiseUnderLightPath);
  EXPECT_FALSE(c.metadata.cacheable);
  EXPECT_EQ(c.metadata.cutDomain, "uv");
  EXPECT_EQ(c.metadata.cutWidth, 3u);  // the noise's Color
  EXPECT_NE(c.cut.find("NoiseTexture"), std::string::npos) << c.cut;
  EXPECT_EQ(c.cut.find("LightPath"), std::string::npos) << c.cut;
  EXPECT_EQ(c.cut.find("inputs.ray"), std::string::npos) << c.cut;
  EXPECT_NE(c.rest.find("LightPath("), std::string::npos) << c.rest;
  EXPECT_EQ(c.rest.find("NoiseTexture"), std::string::npos) << c.rest;
  const auto& inputs = c.metadata.inputsUsed;
  for (const char* member : {"uv", "rayFlags", "rayDepth"})
    EXPECT_NE(std::find(inputs.begin(), inputs.end(), member), inputs.end()) << member;
}

// A per-ray value entering the noise's coordinates leaves nothing to cache.
TEST(Cut, ANoiseOfTheRayDepthHasNoCut) {
  const auto c = compileReal(
      "material DepthNoise;\n"
      "UVInput Out>1;\n"
      "LightPath RayDepth>2;\n"
      "Add A<1 B<2 Out>3;\n"
      "NoiseTexture Vector<3 Detail=2.0 Color>4;\n"
      "BaseColorOutput In<4;\n");
  EXPECT_EQ(c.metadata.cutDomain, "none");
  EXPECT_TRUE(c.cut.empty());
}

// Object Info's Random is per instance: it joins object space rather than breaking it.
TEST(Cut, PerInstanceInputsJoinTheObjectDomain) {
  const auto c = compileReal(
      "material PerInstance;\n"
      "ObjectInfo Random>1;\n"
      "TextureCoordinate Generated>2;\n"
      "VectorScale In<2 Scale<1 Out>3;\n"
      "NoiseTexture Vector<3 Detail=2.0 Color>4;\n"
      "BaseColorOutput In<4;\n");
  EXPECT_EQ(c.metadata.cutDomain, "object");
  EXPECT_EQ(c.metadata.cutWidth, 3u);
  EXPECT_NEAR(c.metadata.cutCostShare, 1.0, 1e-9);
}

// Two domains each hold a part: the one with more estimated cost wins (a world-space Voronoi,
// 60, over a uv-space noise of one octave, 12).
TEST(Cut, TheDomainHoldingMoreCostWins) {
  const auto c = compileReal(
      "material TwoDomains;\n"
      "UVInput Out>1;\n"
      "NoiseTexture Vector<1 Detail=0.0 Fac>2;\n"
      "PositionInput Out>3;\n"
      "VoronoiTexture Vector<3 Distance>4;\n"
      "Add A<2 B<4 Out>5;\n"
      "RoughnessOutput In<5;\n");
  EXPECT_EQ(c.metadata.cutDomain, "world");
  EXPECT_EQ(c.metadata.cutWidth, 1u);
  EXPECT_NE(c.rest.find("NoiseTexture"), std::string::npos) << c.rest;
  EXPECT_EQ(c.rest.find("VoronoiTexture"), std::string::npos) << c.rest;
}

// The noise's estimated cost scales with its octaves (Detail).
TEST(Cut, NoiseCostScalesWithDetail) {
  auto share = [](const char* detail) {
    return compileReal(std::string("material D;\nUVInput Out>1;\nNoiseTexture Vector<1 Detail=") +
                       detail +
                       " Fac>2;\nLayerWeight Facing>3;\nAdd A<2 B<3 Out>4;\n"
                       "RoughnessOutput In<4;\n")
        .metadata.cutCostShare;
  };
  EXPECT_LT(share("0.0"), share("8.0"));
}

// Each function declares each variable once: the rest's variables initialised from the cut
// are not also produced by a node there, and the cut's nodes are not repeated in the rest.
TEST(Cut, CutAndRestDeclareEachVariableOnce) {
  const auto c = compileReal(kUvPrefixViewTail);
  const std::regex declaration(R"(\n  \w+ ((link|unused)\w+)( = [^;]*)?;)");
  for (const std::string* function : {&c.cut, &c.rest}) {
    ASSERT_FALSE(function->empty());
    std::set<std::string> declared;
    for (std::sregex_iterator it(function->begin(), function->end(), declaration), end; it != end;
         ++it)
      EXPECT_TRUE(declared.insert((*it)[1]).second) << "declared twice: " << (*it)[1];
    EXPECT_FALSE(declared.empty());
  }
  // The noise's two outputs come from the cut, initialised where they are declared.
  EXPECT_NE(c.rest.find("float link2 = cut.v[0];"), std::string::npos) << c.rest;
  EXPECT_NE(c.rest.find("float3 link3 = float3(cut.v[1], cut.v[2], cut.v[3]);"), std::string::npos)
      << c.rest;
}

std::string hostCall(const std::string& name) {
  return "\nfloat4 mg_SampleTexture(int textureIndex, float2 uv, float2 ddx, float2 ddy) {\n"
         "  return float4(uv, ddx.x + ddy.y, float(textureIndex));\n}\n"
         "float4 mgCutThenRest(MaterialInputs inputs) {\n"
         "  MaterialCut_" +
         name + " cut;\n  EvaluateMaterialCut_" + name +
         "(inputs, cut);\n  MaterialOutputs outputs;\n  EvaluateMaterialRest_" + name +
         "(inputs, cut, outputs);\n"
         "  return float4(outputs.baseColor, outputs.roughness);\n}\n";
}

TEST(Cut, CutAndRestCompileWithGlslangForBothTargets) {
  for (const char* graph : {kUvPrefixViewTail, kGeneratedUnderLayerWeight, kUvNoiseUnderLightPath,
                            kBumpOverGeneratedNoise, kBumpOverUvNoise}) {
    const auto run = compileText(graph, realLibrary());
    ASSERT_TRUE(run.material) << run.messages();
    const auto& m = *run.material;
    const auto glsl = memograph::testing::compileGlslCode(m.glsl + hostCall(m.metadata.name));
    EXPECT_TRUE(glsl.ok) << glsl.log;
    const auto hlsl = memograph::testing::compileHlslCode(m.hlsl + hostCall(m.metadata.name));
    EXPECT_TRUE(hlsl.ok) << hlsl.log;
  }
}

// The check above reaches the rest's body: a rest that reads a member the cut lacks fails.
TEST(Cut, GlslangCheckOfTheRestCanFail) {
  const auto run = compileText(kUvPrefixViewTail, realLibrary());
  ASSERT_TRUE(run.material);
  std::string broken = run.material->glsl;
  const std::size_t at = broken.find("cut.v[0]", broken.find("void EvaluateMaterialRest_"));
  ASSERT_NE(at, std::string::npos);
  broken.replace(at, 8, "cut.w[0]");
  EXPECT_FALSE(memograph::testing::compileGlslCode(broken + hostCall("UvTail")).ok);
}

TEST(Cut, OutputIsByteIdenticalAcrossRuns) {
  const auto first = compileText(kGeneratedUnderLayerWeight, realLibrary());
  const auto second = compileText(kGeneratedUnderLayerWeight, realLibrary());
  ASSERT_TRUE(first.material && second.material);
  EXPECT_EQ(first.material->glsl, second.material->glsl);
  EXPECT_EQ(first.material->hlsl, second.material->hlsl);
  EXPECT_EQ(first.material->metadataJson, second.material->metadataJson);
}

// The material's own functions (whole, cut, rest) of one material with a cut, both targets,
// and its metadata. Set MEMOGRAPH_UPDATE_GOLDEN=1 to rewrite them after an intended change.
void expectGoldenCutAndRest(const char* graph, const std::string& stem) {
  const auto run = compileText(graph, realLibrary(), "cut.mgraph");
  ASSERT_TRUE(run.material) << run.messages();
  const std::string dir = std::string(MEMOGRAPH_TEST_DATA_DIR) + "/../golden/";
  const auto& m = *run.material;
  const std::pair<std::string, std::string> files[] = {
      {stem + ".glsl", m.glsl.substr(m.glsl.find("\nvoid Evaluate"))},
      {stem + ".hlsl", m.hlsl.substr(m.hlsl.find("\nvoid Evaluate"))},
      {stem + ".json", m.metadataJson}};
  for (const auto& [file, actual] : files) {
    if (std::getenv("MEMOGRAPH_UPDATE_GOLDEN")) {
      std::ofstream(dir + file, std::ios::binary) << actual;
      continue;
    }
    std::string expected;
    try {
      expected = memograph::testing::readTextFile(dir + file);
    } catch (const std::exception&) {
      FAIL() << "missing golden file " << dir + file << " (run with MEMOGRAPH_UPDATE_GOLDEN=1)";
    }
    EXPECT_EQ(actual, expected) << "generated code differs from " << dir + file;
  }
}

TEST(Cut, GoldenCutAndRestFunctions) {
  expectGoldenCutAndRest(kGeneratedUnderLayerWeight, "cut_generated_under_layer_weight");
}

// A height with its object-space gradient: the two runs and the chain rule.
TEST(Cut, GoldenGradientCut) {
  expectGoldenCutAndRest(kBumpOverGeneratedNoise, "cut_bump_over_generated_noise");
}

// Light Path's per-ray inputs read in the rest, never in the cut.
TEST(Cut, GoldenLightPathInTheRest) {
  expectGoldenCutAndRest(kUvNoiseUnderLightPath, "cut_uv_noise_under_light_path");
}

}  // namespace
}  // namespace memograph::compiler
