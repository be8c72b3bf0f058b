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
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "tools/io/scene_import.h"

namespace {

std::string folder;

void removeFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
}

bool writeFile(const std::string& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), std::streamsize(size));
  return bool(out);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string pattern = (std::filesystem::temp_directory_path() / "memograph-import-fuzz-XXXXXX");
  if (!::mkdtemp(pattern.data())) {
    std::perror("mkdtemp");
    std::abort();
  }
  folder = pattern;
  std::atexit(removeFolder);
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
  if (!writeFile(folder + "/fuzz.bin", bin.data(), bin.size()))
    std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const bool glb = data[0] & 1;
  const std::string path = folder + (glb ? "/fuzz.glb" : "/fuzz.gltf");
  if (!writeFile(path, data + 1, size - 1))
    std::abort();
  memograph::compiler::Diagnostics diagnostics;
  const auto scene = memograph::io::importScene(path, "", diagnostics);
  std::filesystem::remove(path);
  if (!scene) {
    if (!diagnostics.hasErrors()) {
      std::fprintf(stderr, "import failed without an error\n");
      std::abort();
    }
    return 0;
  }
  for (const auto& mesh : scene->meshes) {
    for (std::uint32_t index : mesh.indices) {
      if (index >= mesh.positions.size()) {
        std::fprintf(stderr, "accepted a vertex index %u of %zu vertices\n", index,
                     mesh.positions.size());
        std::abort();
      }
    }
  }
  for (const auto& instance : scene->instances) {
    if (instance.mesh >= scene->meshes.size() || instance.material >= scene->materials.size()) {
      std::fprintf(stderr, "accepted an instance out of range\n");
      std::abort();
    }
  }
  return 0;
}
