// The real node library (nodes/): it loads without a diagnostic, every instantiated function
// of it (every overload of every node, every helper) compiles with glslang as GLSL and as
// HLSL, and every node that has a derivative overload is reachable by type inference.
#include <gtest/gtest.h>

#include "glslang_check.h"
#include "test_support.h"

namespace memograph::compiler {
namespace {

using memograph::testing::realLibrary;

// Every library function, callees before callers (the order the emitter uses): the whole
// prelude (which holds the prelude's functions), then the families' functions.
std::string wholeLibrary(Target target) {
  const auto& functions = realLibrary().functions();
  std::vector<char> visited(functions.size(), 0);
  std::string code = realLibrary().prelude(target);
  for (std::size_t root = 0; root < functions.size(); ++root) {
    if (visited[root])
      continue;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{root, 0}};
    visited[root] = 1;
    while (!stack.empty()) {
      auto& [function, next] = stack.back();
      if (next < functions[function].callees.size()) {
        const std::size_t callee = functions[function].callees[next++];
        if (!visited[callee]) {
          visited[callee] = 1;
          stack.emplace_back(callee, 0);
        }
        continue;
      }
      if (!functions[function].prelude)
        code += functions[function].text + "\n";
      stack.pop_back();
    }
  }
  return code;
}

TEST(RealNodeLibrary, HasTheNodesTheIssueAsksFor) {
  for (const char* name : {"Float1Constant",
                           "UVInput",
                           "NormalInput",
                           "PositionInput",
                           "TangentInput",
                           "VertexColorInput",
                           "ViewInput",
                           "TimeInput",
                           "BaseColorOutput",
                           "MetallicOutput",
                           "RoughnessOutput",
                           "NormalOutput",
                           "EmissionOutput",
                           "OpacityOutput",
                           "Add",
                           "Mul",
                           "Mix",
                           "Clamp",
                           "MapRange",
                           "Dot",
                           "Cross",
                           "Normalize",
                           "Length",
                           "SeparateXYZ",
                           "CombineXYZ",
                           "ColorRamp",
                           "NoiseTexture",
                           "VoronoiTexture",
                           "CheckerTexture",
                           "BrickTexture",
                           "GradientTexture",
                           "ImageTexture",
                           "ImageTextureClosest",
                           "ImageTextureBilinear",
                           "ImageTextureBicubic",
                           "ImageTextureBox",
                           "ImageProjection",
                           "NormalMap",
                           "Bump",
                           "NormalFromPosition",
                           "CheckerTextureFiltered",
                           "Mapping",
                           "VectorRotate",
                           "VectorTransform",
                           "Normal",
                           "TextureCoordinate",
                           "UVMap",
                           "Geometry",
                           "Tangent",
                           "Attribute",
                           "ObjectInfo",
                           "Fresnel",
                           "LayerWeight"}) {
    EXPECT_NE(realLibrary().find(name), nullptr) << name;
  }
  EXPECT_GE(realLibrary().nodeTypes().size(), 80u);
}

TEST(RealNodeLibrary, EveryFunctionCompilesAsGlsl) {
  const auto check = testing::compileGlslCode(wholeLibrary(Target::Glsl));
  EXPECT_TRUE(check.ok) << check.log;
}

TEST(RealNodeLibrary, EveryFunctionCompilesAsHlsl) {
  const auto check = testing::compileHlslCode(wholeLibrary(Target::Hlsl));
  EXPECT_TRUE(check.ok) << check.log;
}

TEST(RealNodeLibrary, TheseChecksCatchABrokenUncalledFunction) {
  const std::string broken = "\nfloat mg_broken(float x) { return undefinedThing + x; }\n";
  EXPECT_FALSE(testing::compileGlslCode(wholeLibrary(Target::Glsl) + broken).ok);
  EXPECT_FALSE(testing::compileHlslCode(wholeLibrary(Target::Hlsl) + broken).ok);
}

TEST(RealNodeLibrary, MostNodesOfferADerivativeOverload) {
  std::size_t withDerivatives = 0, eligible = 0;
  for (const auto& node : realLibrary().nodeTypes()) {
    if (node.isSink)
      continue;
    ++eligible;
    for (const auto& overload : node.overloads) {
      if (overload.derivativeOutputs > 0) {
        ++withDerivatives;
        break;
      }
    }
  }
  // Sinks aside, only nodes that consume derivatives (Bump, NormalFromPosition, NormalMap)
  // or have no meaningful ones may lack a _D output.
  EXPECT_GE(withDerivatives + 6, eligible) << withDerivatives << " of " << eligible;
}

}  // namespace
}  // namespace memograph::compiler
