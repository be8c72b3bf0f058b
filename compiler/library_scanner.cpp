#include "compiler/library_scanner.h"

#include <cctype>

namespace memograph::compiler {

namespace {

bool isWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

class Scanner {
 public:
  Scanner(const SourceFile& file, Diagnostics& diagnostics)
      : file_(file), text_(file.text), diagnostics_(diagnostics) {}

  std::vector<LibraryItem> run() {
    std::vector<LibraryItem> items;
    std::vector<std::string> doc;
    while (!failed_) {
      skipBlankKeepingDoc(doc);
      if (position_ >= text_.size())
        break;
      LibraryItem item;
      item.location = here();
      const std::size_t start = position_;
      if (text_[position_] == '#') {
        item.kind = LibraryItem::Kind::Preprocessor;
        preprocessorLine();
      } else if (wordAt("struct")) {
        item.kind = LibraryItem::Kind::Struct;
        if (!structDefinition())
          break;
      } else {
        item.kind = LibraryItem::Kind::Function;
        if (!functionDefinition(item))
          break;
      }
      item.text = std::string(text_.substr(start, position_ - start));
      item.docLines = std::move(doc);
      doc.clear();
      items.push_back(std::move(item));
    }
    return items;
  }

 private:
  SourceLocation here() const {
    return {line_, static_cast<std::uint32_t>(position_ - lineStart_ + 1)};
  }

  void advance() {
    if (text_[position_] == '\n') {
      ++line_;
      lineStart_ = position_ + 1;
    }
    ++position_;
  }

  void fail(SourceLocation at, std::string message) {
    diagnostics_.error(file_, at, std::move(message));
    failed_ = true;
  }

  bool startsWith(std::string_view prefix) const {
    return text_.substr(position_, prefix.size()) == prefix;
  }

  bool wordAt(std::string_view word) const {
    return startsWith(word) &&
           (position_ + word.size() >= text_.size() || !isWordChar(text_[position_ + word.size()]));
  }

  void skipLine() {
    while (position_ < text_.size() && text_[position_] != '\n')
      advance();
  }

  // Skips whitespace and comments; `///` lines accumulate into `doc`, which a blank line or
  // a non-doc comment clears (a doc comment belongs to the item right below it).
  void skipBlankKeepingDoc(std::vector<std::string>& doc) {
    int newlines = 0;
    while (position_ < text_.size()) {
      const char c = text_[position_];
      if (c == '\n') {
        if (++newlines >= 2)
          doc.clear();
        advance();
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        advance();
      } else if (startsWith("///")) {
        position_ += 3;
        const std::size_t start = position_;
        skipLine();
        std::string line(text_.substr(start, position_ - start));
        const auto first = line.find_first_not_of(" \t");
        const auto last = line.find_last_not_of(" \t\r");
        doc.push_back(first == std::string::npos ? "" : line.substr(first, last - first + 1));
        newlines = 0;
      } else if (startsWith("//")) {
        doc.clear();
        skipLine();
      } else if (startsWith("/*")) {
        doc.clear();
        if (!skipBlockComment())
          return;
      } else {
        return;
      }
    }
  }

  bool skipBlockComment() {
    const SourceLocation at = here();
    position_ += 2;
    while (position_ < text_.size() && !startsWith("*/"))
      advance();
    if (position_ >= text_.size()) {
      fail(at, "unterminated /* comment");
      return false;
    }
    position_ += 2;
    return true;
  }

  void preprocessorLine() {
    // Lines ending in a backslash continue the directive.
    while (position_ < text_.size()) {
      if (text_[position_] == '\n' && (position_ == 0 || text_[position_ - 1] != '\\'))
        break;
      advance();
    }
  }

  void skipSpace() {
    while (position_ < text_.size()) {
      if (std::isspace(static_cast<unsigned char>(text_[position_]))) {
        advance();
      } else if (startsWith("//")) {
        skipLine();
      } else if (startsWith("/*")) {
        if (!skipBlockComment())
          return;
      } else {
        return;
      }
    }
  }

  std::string_view word() {
    const std::size_t start = position_;
    while (position_ < text_.size() && isWordChar(text_[position_]))
      advance();
    return text_.substr(start, position_ - start);
  }

  // Moves past the bracket that closes the one at the current position.
  bool matchBrackets(char open, char close) {
    const SourceLocation at = here();
    int depth = 0;
    while (position_ < text_.size() && !failed_) {
      if (startsWith("//")) {
        skipLine();
        continue;
      }
      if (startsWith("/*")) {
        if (!skipBlockComment())
          return false;
        continue;
      }
      const char c = text_[position_];
      advance();
      if (c == open)
        ++depth;
      if (c == close && --depth == 0)
        return true;
    }
    if (!failed_)
      fail(at, std::string("this '") + open + "' is never closed");
    return false;
  }

  bool structDefinition() {
    word();  // struct
    skipSpace();
    const SourceLocation nameAt = here();
    if (word().empty()) {
      fail(nameAt, "expected a struct name");
      return false;
    }
    skipSpace();
    if (position_ >= text_.size() || text_[position_] != '{') {
      fail(here(), "expected '{' after the struct name");
      return false;
    }
    if (!matchBrackets('{', '}'))
      return false;
    skipSpace();
    if (position_ >= text_.size() || text_[position_] != ';') {
      fail(here(), "expected ';' after the struct's '}'");
      return false;
    }
    advance();
    return true;
  }

  bool functionDefinition(LibraryItem& item) {
    const SourceLocation at = here();
    item.returnType = std::string(word());
    skipSpace();
    item.name = std::string(word());
    skipSpace();
    if (item.returnType.empty() || item.name.empty() || position_ >= text_.size() ||
        text_[position_] != '(') {
      fail(at,
           "expected a function definition `Type Name(parameters) { … }`, a struct or a "
           "preprocessor line (node files hold nothing else: no globals or constants)");
      return false;
    }
    const std::size_t listStart = position_ + 1;
    if (!matchBrackets('(', ')'))
      return false;
    item.parameterList = std::string(text_.substr(listStart, position_ - 1 - listStart));
    skipSpace();
    if (position_ < text_.size() && text_[position_] == ';') {
      advance();
      item.isPrototype = true;
      return true;
    }
    if (position_ >= text_.size() || text_[position_] != '{') {
      fail(here(),
           "expected the body '{' or ';' after the parameters of function '" + item.name + "'");
      return false;
    }
    return matchBrackets('{', '}');
  }

  const SourceFile& file_;
  std::string_view text_;
  Diagnostics& diagnostics_;
  std::size_t position_ = 0;
  std::size_t lineStart_ = 0;
  std::uint32_t line_ = 1;
  bool failed_ = false;
};

}  // namespace

std::vector<LibraryItem> scanLibraryFile(const SourceFile& file, Diagnostics& diagnostics) {
  return Scanner(file, diagnostics).run();
}

std::string replaceWord(std::string_view text, std::string_view word, std::string_view with) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    if (isWordChar(text[i])) {
      std::size_t j = i;
      while (j < text.size() && isWordChar(text[j]))
        ++j;
      // Segments between underscores are replaced too, so `T_D` and `mg_make_T_D` follow T.
      const std::string_view token = text.substr(i, j - i);
      std::size_t segmentStart = 0;
      while (segmentStart <= token.size()) {
        auto segmentEnd = token.find('_', segmentStart);
        if (segmentEnd == std::string_view::npos)
          segmentEnd = token.size();
        const auto segment = token.substr(segmentStart, segmentEnd - segmentStart);
        out += segment == word ? with : segment;
        if (segmentEnd < token.size())
          out += '_';
        segmentStart = segmentEnd + 1;
      }
      i = j;
    } else {
      out += text[i++];
    }
  }
  return out;
}

std::vector<std::string_view> identifiersIn(std::string_view text) {
  std::vector<std::string_view> result;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text.substr(i, 2) == "//") {
      while (i < text.size() && text[i] != '\n')
        ++i;
    } else if (text.substr(i, 2) == "/*") {
      const auto end = text.find("*/", i + 2);
      i = end == std::string_view::npos ? text.size() : end + 2;
    } else if (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') {
      std::size_t j = i;
      while (j < text.size() && isWordChar(text[j]))
        ++j;
      result.push_back(text.substr(i, j - i));
      i = j;
    } else if (std::isdigit(static_cast<unsigned char>(text[i]))) {
      while (i < text.size() && isWordChar(text[i]))
        ++i;  // 1.0f, 0x1F: not identifiers
    } else {
      ++i;
    }
  }
  return result;
}

}  // namespace memograph::compiler
