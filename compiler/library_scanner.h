// Splits a node-library file into its top-level items (doc comments, preprocessor lines,
// structs, function definitions) without understanding the shading language beyond
// brackets and comments. The loader (node_library.cpp) gives the items meaning.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

struct LibraryItem {
  enum class Kind { Preprocessor, Struct, Function };
  Kind kind = Kind::Function;
  std::string text;                   // the item's full source text
  std::vector<std::string> docLines;  // `///` lines just above it, without the slashes
  SourceLocation location;
  // Functions only: the pieces of the signature.
  std::string returnType;
  std::string name;
  std::string parameterList;  // text between the parentheses
  bool isPrototype = false;   // `Type name(params);` — allowed in the prelude only
};

std::vector<LibraryItem> scanLibraryFile(const SourceFile& file, Diagnostics& diagnostics);

// Replaces whole-word occurrences of `word` in `text`, and occurrences between underscores
// inside identifiers (`T_D`, `mg_make_T_D`): the @types substitution.
std::string replaceWord(std::string_view text, std::string_view word, std::string_view with);

// The identifiers in `text`, comments skipped (used to find which functions a body calls).
std::vector<std::string_view> identifiersIn(std::string_view text);

}  // namespace memograph::compiler
