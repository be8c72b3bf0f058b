// The one way to get the node library the tools use: the copy embedded at build time, or
// the *.inc files of a folder (for library authors: `--nodes DIR`).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/node_library.h"
#include "compiler/source_file.h"

namespace memograph::nodes {

// The library's files: embedded when `directory` is empty, else read from it. Nothing
// (after an error in `diagnostics`) when the folder is missing or a file unreadable.
std::optional<std::vector<compiler::SourceFile>> nodeLibrarySources(
    const std::string& directory, compiler::Diagnostics& diagnostics);

// nodeLibrarySources, parsed. Nothing when the library has an error.
std::optional<compiler::NodeLibrary> loadNodeLibrary(const std::string& directory,
                                                     compiler::Diagnostics& diagnostics);

}  // namespace memograph::nodes
