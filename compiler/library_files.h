// Reads a node library from disk: every *.inc file under a directory, named by its path
// relative to that directory ("prelude/common.inc", "math.inc").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

std::optional<std::vector<SourceFile>> readNodeLibraryDirectory(const std::string& directory,
                                                                Diagnostics& diagnostics);

}  // namespace memograph::compiler
