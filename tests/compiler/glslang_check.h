// Compiles generated material includes with glslang's library, in-process, the way a
// renderer would include them: GLSL through the GLSL front end, HLSL through the HLSL one,
// each inside a small compute shader that calls EvaluateMaterial_<Name>.
#pragma once

#include <string>
#include <vector>

namespace memograph::testing {

struct ShaderCheck {
  bool ok = false;
  std::string log;  // glslang's messages when not ok
};

// `includes` are complete material includes for one target; `names` their material names.
// Several materials go into one shader, which also checks that their guards let them
// coexist.
ShaderCheck compileGlslMaterials(const std::vector<std::string>& includes,
                                 const std::vector<std::string>& names);
ShaderCheck compileHlslMaterials(const std::vector<std::string>& includes,
                                 const std::vector<std::string>& names);

// Compiles arbitrary shader code (no material call) with an empty compute entry point;
// glslang still type-checks every function in it.
ShaderCheck compileGlslCode(const std::string& code);
ShaderCheck compileHlslCode(const std::string& code);

}  // namespace memograph::testing
