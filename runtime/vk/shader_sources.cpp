#include "runtime/vk/shader_sources.h"

namespace memograph::runtime {

std::map<std::string, std::string> embeddedShaderFiles() {
  std::map<std::string, std::string> files;
  for (const ShaderSource& shader : embeddedShaders())
    files[std::string(shader.name)] = std::string(shader.text);
  return files;
}

}  // namespace memograph::runtime
