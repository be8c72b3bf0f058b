// The runtime's GLSL sources (runtime/shaders/*), embedded at build time.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>

namespace memograph::runtime {

struct ShaderSource {
  std::string_view name;  // file name, e.g. "path_tracer.glsl"
  std::string_view text;
};

std::span<const ShaderSource> embeddedShaders();

// The same sources as a ShaderCompiler's file map (name to text), to which a caller adds
// its own generated files.
std::map<std::string, std::string> embeddedShaderFiles();

}  // namespace memograph::runtime
