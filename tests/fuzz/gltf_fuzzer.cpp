// libFuzzer entry point: any bytes as a .gltf (first byte even) or .glb (odd) file through
// the glTF pre-check (tools/io/gltf_precheck.h), which stands between a file and assimp: it
// must never crash, recurse without bound or allocate what a header declares, and a
// rejection must carry an error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "tools/io/gltf_precheck.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const bool glb = data[0] & 1;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  memograph::compiler::Diagnostics diagnostics;
  if (!memograph::io::precheckGltfBytes(glb ? "fuzz.glb" : "fuzz.gltf", bytes, glb, diagnostics) &&
      !diagnostics.hasErrors())
    std::abort();
  return 0;
}
