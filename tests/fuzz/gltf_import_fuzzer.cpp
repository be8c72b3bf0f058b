// libFuzzer entry point: any bytes as a .gltf (first byte even) or .glb (odd) file through
// the real importer (io::importScene: the pre-check, assimp, memograph's conversion and
// runtime::validateScene). It must never crash or hang; a failed import must carry an
// error, and an accepted scene must hold only what the renderer relies on (every vertex
// index below its mesh's vertex count, every instance's mesh and material in range).
//
// assimp reads files by name, so each input is written to fuzz.gltf or fuzz.glb in a
// private folder that also holds fuzz.bin, a valid external buffer (the one triangle of
// tests/adversarial/make_scenes.py: nine floats of positions, then indices 0 1 2 as
// unsigned shorts and two bytes of padding), for inputs whose buffers name it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "tests/fuzz/fuzz_folder.h"
#include "tests/fuzz/imported_scene_checks.h"
#include "tools/io/scene_import.h"

namespace {

std::string folder;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  folder = memograph::fuzz::makePrivateFolder("import");
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
  if (!memograph::fuzz::writeFile(folder + "/fuzz.bin", bin))
    std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const bool glb = data[0] & 1;
  const std::string path = folder + (glb ? "/fuzz.glb" : "/fuzz.gltf");
  if (!memograph::fuzz::writeFile(path, {reinterpret_cast<const char*>(data + 1), size - 1}))
    std::abort();
  memograph::compiler::Diagnostics diagnostics;
  const auto scene = memograph::io::importScene(path, "", diagnostics);
  std::filesystem::remove(path);
  memograph::fuzz::checkImportedScene(scene, diagnostics);
  return 0;
}
