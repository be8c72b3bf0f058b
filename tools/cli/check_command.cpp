// memograph check FILE: every link's inferred type and whether it carries derivatives.
#include <iomanip>
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "compiler/compiler.h"
#include "compiler/library_files.h"
#include "compiler/metadata.h"

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph check FILE [--nodes DIR]\n"
    "\n"
    "Type-checks a material graph without writing anything and prints the overload chosen\n"
    "for each node, each link's inferred type, whether it carries derivatives (_D), and the\n"
    "material's metadata. Exit code 0 when the graph compiles, 1 when it does not.\n";

std::string joinOrNone(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items)
    text += (text.empty() ? "" : ", ") + item;
  return text.empty() ? "none" : text;
}

}  // namespace

int runCheck(std::span<const std::string_view> args) {
  std::string nodesDir;
  ArgumentScanner scanner("check", args);
  scanner.option("--nodes", &nodesDir);
  scanner.help(kHelp);
  std::vector<std::string> files;
  if (const auto exitCode = scanner.scan(files))
    return *exitCode;
  if (files.size() != 1)
    return usageError("check", "expected exactly one graph file");
  if (scanner.given("--nodes")) {
    if (const auto problem = compiler::nodeLibraryDirectoryProblem(nodesDir))
      return usageError("check", "--nodes " + nodesDir + ": " + *problem);
  }

  compiler::Diagnostics diagnostics;
  const auto library = loadNodeLibrary(nodesDir, diagnostics);
  std::string error;
  const auto text = library ? readFile(files[0], error) : std::nullopt;
  if (library && !text)
    diagnostics.error(files[0], error);
  std::optional<compiler::CheckReport> report;
  if (text)
    report = compiler::checkMaterial({files[0], *text}, *library, diagnostics);
  printDiagnostics(diagnostics);
  if (!report)
    return kExitFailure;

  const auto& meta = report->metadata;
  std::cout << "material " << meta.name << ": " << meta.nodeCount << " nodes, "
            << (meta.cacheable ? "cacheable" : "not cacheable") << ", derivatives "
            << (meta.needsDerivatives ? "used" : "not used") << "\n"
            << "  inputs:   " << joinOrNone(meta.inputsUsed) << "\n"
            << "  outputs:  " << joinOrNone(meta.outputsWritten) << "\n"
            << "  textures: " << joinOrNone(meta.textures) << "\n"
            << "  cut:      "
            << (meta.cutDomain == "none"
                    ? std::string("none")
                    : meta.cutDomain + " key, " + std::to_string(meta.cutWidth) + " floats, " +
                          compiler::formatShare(meta.cutCostShare) + " of the estimated cost")
            << "\n\nnodes (emission order):\n";
  for (const auto& node : report->nodes)
    std::cout << "  " << node << "\n";
  std::cout << "\nlinks:\n";
  for (const auto& link : report->links) {
    std::cout << "  " << std::left << std::setw(10) << link.name << std::setw(10) << link.type
              << (link.derivatives ? "deriv  " : "plain  ") << link.producer << " -> "
              << joinOrNone(link.consumers) << "\n";
  }
  return kExitOk;
}

}  // namespace memograph::cli
