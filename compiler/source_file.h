// A named source text (a .mgraph graph or a node-library file) and positions inside it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace memograph::compiler {

// 1-based line and column; column counts bytes. {0, 0} means "no position".
struct SourceLocation {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

struct SourceFile {
  std::string path;  // as the user named it; printed in diagnostics
  std::string text;

  // The text of a 1-based line without its line break (empty when out of range).
  std::string_view lineText(std::uint32_t line) const;
};

}  // namespace memograph::compiler
