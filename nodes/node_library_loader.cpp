#include "memograph/node_library_loader.h"

#include "compiler/library_files.h"
#include "memograph/embedded_node_library.h"

namespace memograph::nodes {

std::optional<std::vector<compiler::SourceFile>> nodeLibrarySources(
    const std::string& directory, compiler::Diagnostics& diagnostics) {
  if (!directory.empty())
    return compiler::readNodeLibraryDirectory(directory, diagnostics);
  std::vector<compiler::SourceFile> files;
  for (const auto& embedded : embeddedNodeLibrary()) {
    files.push_back({std::string(embedded.path), std::string(embedded.text)});
  }
  if (files.empty()) {
    diagnostics.error("<built-in>", "the built-in node library is empty");
    return std::nullopt;
  }
  return files;
}

std::optional<compiler::NodeLibrary> loadNodeLibrary(const std::string& directory,
                                                     compiler::Diagnostics& diagnostics) {
  const auto files = nodeLibrarySources(directory, diagnostics);
  if (!files)
    return std::nullopt;
  const std::size_t errorsBefore = diagnostics.errorCount();
  auto library = compiler::NodeLibrary::load(*files, diagnostics);
  if (diagnostics.errorCount() > errorsBefore)
    return std::nullopt;
  return library;
}

}  // namespace memograph::nodes
