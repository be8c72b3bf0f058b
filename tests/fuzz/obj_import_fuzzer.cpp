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

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "runtime/scene/scene_limits.h"
#include "tests/fuzz/fuzz_folder.h"
#include "tests/fuzz/imported_scene_checks.h"
#include "tools/io/scene_import.h"

namespace {

std::string folder;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  folder = memograph::fuzz::makePrivateFolder("obj");
  if (::mkfifo((folder + "/fifo.mtl").c_str(), 0600) != 0 ||
      !std::filesystem::create_directory(folder + "/folder.mtl"))
    std::abort();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string obj = folder + "/fuzz.obj", mtl = folder + "/fuzz.mtl";
  if (!memograph::fuzz::writeFile(obj, input.substr(0, split)))
    std::abort();
  std::filesystem::remove(mtl);
  if (split != std::string_view::npos && !memograph::fuzz::writeFile(mtl, input.substr(split + 1)))
    std::abort();
  memograph::compiler::Diagnostics diagnostics;
  const auto scene = memograph::io::importScene(obj, "", diagnostics);
  memograph::fuzz::checkImportedScene(scene, diagnostics);
  if (scene && scene->meshes.size() > memograph::runtime::kMaxSceneMeshes) {
    std::fprintf(stderr, "accepted %zu meshes\n", scene->meshes.size());
    std::abort();
  }
  return 0;
}
