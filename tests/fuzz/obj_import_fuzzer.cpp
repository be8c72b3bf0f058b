// libFuzzer entry point: any bytes as an OBJ file and its material library through the real
// importer (io::importScene: the OBJ pre-check, the guard on every file assimp opens,
// assimp, memograph's conversion and runtime::validateScene). It must never crash or hang;
// a failed import must carry an error, and an accepted scene must hold only what the
// renderer relies on (every vertex index below its mesh's vertex count, every instance's
// mesh and material in range, no more meshes than the scene limit).
//
// The input up to its first NUL byte is fuzz.obj; the rest, if any, is fuzz.mtl, which an
// input names with `mtllib fuzz.mtl` (and which assimp opens as the fallback library of
// fuzz.obj). The private folder also holds a FIFO, fifo.mtl, and a folder, folder.mtl, for
// inputs that name them: neither may block or be read.
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "runtime/scene/scene_limits.h"
#include "tools/io/scene_import.h"

namespace {

std::string folder;

void removeFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
}

bool writeFile(const std::string& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  return bool(out);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string pattern = (std::filesystem::temp_directory_path() / "memograph-obj-fuzz-XXXXXX");
  if (!::mkdtemp(pattern.data())) {
    std::perror("mkdtemp");
    std::abort();
  }
  folder = pattern;
  std::atexit(removeFolder);
  if (::mkfifo((folder + "/fifo.mtl").c_str(), 0600) != 0 ||
      !std::filesystem::create_directory(folder + "/folder.mtl"))
    std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string obj = folder + "/fuzz.obj", mtl = folder + "/fuzz.mtl";
  if (!writeFile(obj, input.substr(0, split)))
    std::abort();
  std::filesystem::remove(mtl);
  if (split != std::string_view::npos && !writeFile(mtl, input.substr(split + 1)))
    std::abort();
  memograph::compiler::Diagnostics diagnostics;
  const auto scene = memograph::io::importScene(obj, "", diagnostics);
  if (!scene) {
    if (!diagnostics.hasErrors()) {
      std::fprintf(stderr, "import failed without an error\n");
      std::abort();
    }
    return 0;
  }
  if (scene->meshes.size() > memograph::runtime::kMaxSceneMeshes) {
    std::fprintf(stderr, "accepted %zu meshes\n", scene->meshes.size());
    std::abort();
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
