// Reads a node library from disk: every *.inc file under a directory, named by its path
// relative to that directory ("prelude/common.inc", "math.inc").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

// Why `directory` cannot be a node library folder ("does not exist", "is not a folder"), or
// nothing. Commands check `--nodes DIR` with it among their options, before any work.
std::optional<std::string> nodeLibraryDirectoryProblem(const std::string& directory);

std::optional<std::vector<SourceFile>> readNodeLibraryDirectory(const std::string& directory,
                                                                Diagnostics& diagnostics);

}  // namespace memograph::compiler
