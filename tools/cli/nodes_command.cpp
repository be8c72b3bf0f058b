// memograph nodes [NAME…]: the node library, with sockets, defaults and overloads.
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "compiler/literal.h"
#include "compiler/type_inference.h"

namespace memograph::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: memograph nodes [NAME...] [--nodes DIR] [--brief]\n"
    "\n"
    "Lists the node library: each node's description, sockets with their defaults, and\n"
    "every overload (types ending in _D carry derivatives). With NAMEs, only those nodes.\n"
    "\n"
    "options:\n"
    "  --nodes DIR   read the library from DIR instead of the built-in one\n"
    "  --brief       one line per node\n";

std::string literalText(const compiler::Literal& value) {
  if (value.kind == compiler::Literal::Kind::Number && value.isInteger) {
    return std::to_string(static_cast<long long>(value.components[0]));
  }
  if (value.components.size() == 1)
    return compiler::formatFloat(value.components[0]);
  std::string text = "(";
  for (std::size_t i = 0; i < value.components.size(); ++i) {
    text += (i ? ", " : "") + compiler::formatFloat(value.components[i]);
  }
  return text + ")";
}

}  // namespace

int runNodes(std::span<const std::string_view> args) {
  std::string nodesDir;
  bool brief = false;
  ArgumentScanner scanner("nodes", args);
  scanner.option("--nodes", &nodesDir);
  scanner.flag("--brief", &brief);
  scanner.help(kHelp);
  std::vector<std::string> names;
  if (const auto exitCode = scanner.scan(names))
    return *exitCode;
  compiler::Diagnostics diagnostics;
  const auto library = loadNodeLibrary(nodesDir, diagnostics);
  printDiagnostics(diagnostics);
  if (!library)
    return kExitFailure;
  for (const auto& name : names) {
    if (!library->find(name)) {
      std::cerr << "memograph nodes: no node named '" << name << "'";
      const auto suggestions = library->suggestions(name);
      if (!suggestions.empty())
        std::cerr << " (did you mean '" << suggestions[0] << "'?)";
      std::cerr << "\n";
      return kExitFailure;
    }
  }
  for (const auto& node : library->nodeTypes()) {
    if (!names.empty() && std::find(names.begin(), names.end(), node.name) == names.end()) {
      continue;
    }
    if (brief) {
      std::cout << node.name << " — " << node.description << "\n";
      continue;
    }
    std::cout << node.name << "  (" << node.file << ")\n";
    if (!node.description.empty())
      std::cout << "  " << node.description << "\n";
    for (const auto& socket : node.sockets) {
      std::cout << "  " << (socket.direction == compiler::Direction::In ? "in  " : "out ")
                << socket.name;
      const auto fallback = node.defaults.find(socket.name);
      if (fallback != node.defaults.end())
        std::cout << " = " << literalText(fallback->second);
      std::cout << "\n";
    }
    for (const auto& overload : node.overloads) {
      std::cout << "    " << compiler::overloadSignature(node, overload) << "\n";
    }
    std::cout << "\n";
  }
  return kExitOk;
}

}  // namespace memograph::cli
