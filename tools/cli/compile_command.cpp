// memograph compile FILES… --target glsl|hlsl|both -o DIR
#include <filesystem>
#include <iostream>
#include <map>

#include "cli_common.h"
#include "commands.h"
#include "compiler/compiler.h"
#include "compiler/library_files.h"

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph compile FILE... [--target glsl|hlsl|both] [-o DIR] [--nodes DIR]\n"
    "\n"
    "Compiles each .mgraph material graph to DIR/<Name>.glsl and/or DIR/<Name>.hlsl (an\n"
    "include defining EvaluateMaterial_<Name>) and DIR/<Name>.json (metadata: inputs used,\n"
    "outputs written, cacheability, textures). Nothing is written unless every file\n"
    "compiles.\n"
    "\n"
    "options:\n"
    "  --target T    glsl, hlsl or both (default both)\n"
    "  -o DIR        output directory, created if missing (default .)\n"
    "  --nodes DIR   use the node library in DIR instead of the built-in one\n"
    "  --quiet       print nothing on success\n";

}  // namespace

int runCompile(std::span<const std::string_view> args) {
  std::string target = "both", outputDir = ".", nodesDir;
  bool quiet = false;
  ArgumentScanner scanner("compile", args);
  scanner.option("--target", &target);
  scanner.option("-o", &outputDir);
  scanner.option("--output", &outputDir);
  scanner.option("--nodes", &nodesDir);
  scanner.flag("--quiet", &quiet);
  scanner.help(kHelp);
  std::vector<std::string> files;
  if (const auto exitCode = scanner.scan(files))
    return *exitCode;
  if (target != "glsl" && target != "hlsl" && target != "both") {
    return usageError("compile", "--target must be glsl, hlsl or both, not '" + target + "'");
  }
  if (files.empty())
    return usageError("compile", "no input files");
  if (scanner.given("--nodes")) {
    if (const auto problem = compiler::nodeLibraryDirectoryProblem(nodesDir))
      return usageError("compile", "--nodes " + nodesDir + ": " + *problem);
  }

  // The output folder is checked after every option (a usage error, exit 2, comes first) and
  // before any work: a file in its place is an error now, not after compiling everything.
  if (std::error_code ec;
      std::filesystem::exists(outputDir, ec) && !std::filesystem::is_directory(outputDir, ec)) {
    std::cerr << "memograph compile: " << outputDir << ": exists and is not a folder\n";
    return kExitFailure;
  }

  compiler::Diagnostics diagnostics;
  const auto library = loadNodeLibrary(nodesDir, diagnostics);
  if (!library) {
    printDiagnostics(diagnostics);
    return kExitFailure;
  }
  compiler::CompileOptions options;
  options.emitGlsl = target != "hlsl";
  options.emitHlsl = target != "glsl";

  std::vector<std::pair<std::string, std::string>> outputs;
  std::map<std::string, std::string> materialSources;  // name → file, to catch clashes
  for (const auto& path : files) {
    std::string error;
    const auto text = readFile(path, error);
    if (!text) {
      diagnostics.error(path, error);
      continue;
    }
    const compiler::SourceFile source{path, *text};
    const auto material = compiler::compileMaterial(source, *library, options, diagnostics);
    if (!material)
      continue;
    const std::string& name = material->metadata.name;
    if (const auto [it, inserted] = materialSources.emplace(name, path); !inserted) {
      diagnostics.error(path, "material '" + name + "' is also defined by " + it->second +
                                  "; rename one (file name or `material Name;`)");
      continue;
    }
    const auto base = (std::filesystem::path(outputDir) / name).string();
    if (options.emitGlsl)
      outputs.emplace_back(base + ".glsl", material->glsl);
    if (options.emitHlsl)
      outputs.emplace_back(base + ".hlsl", material->hlsl);
    outputs.emplace_back(base + ".json", material->metadataJson);
  }
  printDiagnostics(diagnostics);
  if (diagnostics.hasErrors()) {
    std::cerr << diagnostics.errorCount() << (diagnostics.errorCount() == 1 ? " error" : " errors")
              << "; nothing written\n";
    return kExitFailure;
  }
  // No output may replace an input (a graph or node-library file named like an output).
  std::vector<CommandFile> written, read;
  for (const auto& [path, contents] : outputs)
    written.push_back({"-o file", path});
  for (const auto& path : files)
    read.push_back({"FILE", path});
  if (!nodesDir.empty())
    addFolderInputs(read, "--nodes file", nodesDir, ".inc", true);
  if (const int code = refuseOutputOverInput("compile", written, read); code != kExitOk)
    return code;
  std::error_code ec;
  std::filesystem::create_directories(outputDir, ec);
  std::string error;
  // All files or none (files::writeFileSet): a failure part-way restores the files already
  // replaced, and concurrent compiles into one folder commit one after the other.
  if (ec || !writeFilesAtomically(outputs, error)) {
    std::cerr << "memograph compile: " << (ec ? outputDir + ": " + ec.message() : error)
              << "; nothing written\n";
    return kExitFailure;
  }
  if (!quiet) {
    for (const auto& [path, contents] : outputs)
      std::cout << "wrote " << path << "\n";
  }
  return kExitOk;
}

}  // namespace memograph::cli
