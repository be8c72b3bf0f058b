// Parses .mgraph text (thesis Listing 5.1 plus the extensions in docs/guide/graph-format.md)
// into an untyped Graph. Reports every syntax error it can recover from.
#pragma once

#include <cstddef>

#include "compiler/diagnostics.h"
#include "compiler/graph.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

// Graph size limits (docs/guide/limits.md), far above any real material (hundreds of nodes),
// so that the compiler's memory stays bounded whatever a 16 MiB text holds.
inline constexpr std::size_t kMaxGraphNodes = 250'000;
inline constexpr std::size_t kMaxGraphItems = 1'000'000;  // socket bindings and values

// The material name defaults to the file stem, made into an identifier.
Graph parseGraph(const SourceFile& file, Diagnostics& diagnostics);

// "graphs/rusty-metal.mgraph" → "rusty_metal"; never empty, never starts with a digit.
std::string materialNameFromPath(std::string_view path);

}  // namespace memograph::compiler
