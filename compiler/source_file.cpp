#include "compiler/source_file.h"

namespace memograph::compiler {

std::string_view SourceFile::lineText(std::uint32_t line) const {
  if (line == 0)
    return {};
  std::string_view rest = text;
  for (std::uint32_t current = 1; current < line; ++current) {
    const auto newline = rest.find('\n');
    if (newline == std::string_view::npos)
      return {};
    rest.remove_prefix(newline + 1);
  }
  const auto end = rest.find('\n');
  std::string_view result = rest.substr(0, end);
  if (!result.empty() && result.back() == '\r')
    result.remove_suffix(1);
  return result;
}

}  // namespace memograph::compiler
