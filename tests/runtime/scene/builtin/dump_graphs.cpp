// Writes the material graphs of every built-in scene to a folder, one .mgraph per material,
// so they can be compiled with `memograph compile` and inspected by hand.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "runtime/scene/builtin/builtin_scenes.h"

int main(int argc, char** argv) {
  using namespace memograph::runtime;
  if (argc < 2) {
    std::cerr << "usage: scenes_dump_graphs DIR [octaves layers]\n";
    return 2;
  }
  BuiltinSceneOptions options;
  if (argc >= 4)
    options.materialCost = {std::stoi(argv[2]), std::stoi(argv[3])};
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  int count = 0;
  try {
    for (const std::string& name : builtinSceneNames()) {
      const Scene scene = makeBuiltinScene(name, options);
      for (const MaterialRef& m : scene.materials) {
        std::ofstream(dir / (m.name + ".mgraph")) << m.graphText;
        ++count;
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "scenes_dump_graphs: " << e.what() << '\n';
    return 1;
  }
  std::cout << "wrote " << count << " graphs to " << dir.string() << '\n';
  return 0;
}
