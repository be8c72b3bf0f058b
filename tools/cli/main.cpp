// memograph: the command-line front end. Dispatches to one command per file.
#include <filesystem>
#include <iostream>
#include <string_view>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "compiler/input_file.h"
#include "crash_report.h"

namespace memograph::cli {

std::span<const Command> commands() {
  static constexpr Command kCommands[] = {
      {"compile", "compile .mgraph material graphs to GLSL/HLSL includes", runCompile},
      {"check", "type-check a graph and print each link's inferred type", runCheck},
      {"nodes", "list the node library with its overloads", runNodes},
      {"render", "path trace a scene to an HDR image", runRender},
      {"bench", "frames and rays per second on built-in scenes and scene packs", runBench},
      {"bake", "evaluate materials over their UV square into one image per output", runBake},
      {"diff", "perceptual difference of two images (LDR-FLIP) and its error map", runDiff},
      {"import-blender", "export a .blend file's materials as graphs (runs Blender)",
       runImportBlender},
      {"pack", "write an imported scene as one self-contained .mgpack file", runPack},
      {"selftest", "the material cache's concurrency stress test on this GPU", runSelftest},
  };
  return kCommands;
}

namespace {

void printUsage(std::ostream& out) {
  out << "usage: memograph <command> [options]\n\n"
         "memograph compiles material graphs to GLSL and HLSL (and renders them).\n\n"
         "commands:\n";
  for (const auto& command : commands()) {
    out << "  " << command.name
        << std::string(command.name.size() < 10 ? 10 - command.name.size() : 1, ' ')
        << command.summary << "\n";
  }
  out << "\nRun 'memograph <command> --help' for a command's options.\n";
}

}  // namespace

}  // namespace memograph::cli

int main(int argc, char** argv) {
  using namespace memograph::cli;
  installCrashReport();
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.empty()) {
    printUsage(std::cerr);
    return kExitUsage;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    printUsage(std::cout);
    return kExitOk;
  }
  for (const auto& command : commands()) {
    if (command.name == args[0]) {
      try {
        return command.run(std::span(args).subspan(1));
      } catch (const std::bad_alloc&) {
        std::cerr << "memograph " << command.name << ": out of memory\n";
        return kExitFailure;
      } catch (const std::filesystem::filesystem_error& e) {
        // A file problem (a symlink loop, an over-long name) is bad input, not an internal
        // error: name the file and the cause.
        std::cerr << "memograph " << command.name << ": " << e.path1().string() << ": "
                  << memograph::files::describeFileError(e.code()) << "\n";
        return kExitFailure;
      } catch (const std::exception& e) {
        std::cerr << "memograph " << command.name << ": internal error: " << e.what() << "\n";
        return kExitFailure;
      }
    }
  }
  std::cerr << "memograph: unknown command '" << args[0] << "'\n\n";
  printUsage(std::cerr);
  return kExitUsage;
}
