// The runtime's GLSL sources (runtime/shaders/*), embedded at build time.
#pragma once

#include <span>
#include <string_view>

namespace memograph::runtime {

struct ShaderSource {
  std::string_view name;  // file name, e.g. "path_tracer.glsl"
  std::string_view text;
};

std::span<const ShaderSource> embeddedShaders();

}  // namespace memograph::runtime
