#include "compiler/lexer.h"

#include <cctype>
#include <cstdio>

namespace memograph::compiler {

namespace {

bool isIdentifierStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isIdentifierChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

class Lexer {
 public:
  explicit Lexer(std::string_view source) : source_(source) {}

  std::vector<Token> run() {
    std::vector<Token> tokens;
    while (true) {
      skipSpaceAndComments();
      if (position_ >= source_.size())
        break;
      tokens.push_back(next());
    }
    tokens.push_back(Token{TokenKind::End, {}, here(), {}});
    return tokens;
  }

 private:
  SourceLocation here() const { return {line_, column_}; }

  void advance() {
    if (source_[position_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++position_;
  }

  void skipSpaceAndComments() {
    while (position_ < source_.size()) {
      const char c = source_[position_];
      if (c == '#') {
        while (position_ < source_.size() && source_[position_] != '\n')
          advance();
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
        advance();
      } else {
        break;
      }
    }
  }

  Token make(TokenKind kind, std::size_t start, SourceLocation at) {
    return Token{kind, source_.substr(start, position_ - start), at, {}};
  }

  Token next() {
    const SourceLocation at = here();
    const std::size_t start = position_;
    const char c = source_[position_];
    auto single = [&](TokenKind kind) {
      advance();
      return make(kind, start, at);
    };
    switch (c) {
      case '<':
        return single(TokenKind::Less);
      case '>':
        return single(TokenKind::Greater);
      case '=':
        return single(TokenKind::Equals);
      case '(':
        return single(TokenKind::LeftParen);
      case ')':
        return single(TokenKind::RightParen);
      case '[':
        return single(TokenKind::LeftBracket);
      case ']':
        return single(TokenKind::RightBracket);
      case ',':
        return single(TokenKind::Comma);
      case ';':
        return single(TokenKind::Semicolon);
      case '"':
        return string(at);
      default:
        break;
    }
    if (isIdentifierStart(c)) {
      while (position_ < source_.size() && isIdentifierChar(source_[position_]))
        advance();
      return make(TokenKind::Identifier, start, at);
    }
    if (isDigit(c) || ((c == '-' || c == '+' || c == '.') && position_ + 1 < source_.size() &&
                       (isDigit(source_[position_ + 1]) || source_[position_ + 1] == '.'))) {
      return number(start, at);
    }
    advance();
    Token invalid = make(TokenKind::Invalid, start, at);
    const auto byte = static_cast<unsigned char>(c);
    if (std::isprint(byte)) {
      invalid.error = std::string("unexpected character '") + c + "'";
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", byte);
      invalid.error = std::string("unexpected byte ") + hex;
    }
    return invalid;
  }

  // -?digits[.digits][e[+-]digits]; validity of the value is checked by the parser.
  Token number(std::size_t start, SourceLocation at) {
    if (source_[position_] == '-' || source_[position_] == '+')
      advance();
    while (position_ < source_.size() && isDigit(source_[position_]))
      advance();
    if (position_ < source_.size() && source_[position_] == '.') {
      advance();
      while (position_ < source_.size() && isDigit(source_[position_]))
        advance();
    }
    if (position_ < source_.size() && (source_[position_] == 'e' || source_[position_] == 'E')) {
      advance();
      if (position_ < source_.size() && (source_[position_] == '+' || source_[position_] == '-')) {
        advance();
      }
      while (position_ < source_.size() && isDigit(source_[position_]))
        advance();
    }
    // A number glued to letters (`12abc`) is one bad token, not two good ones.
    while (position_ < source_.size() && isIdentifierChar(source_[position_]))
      advance();
    return make(TokenKind::Number, start, at);
  }

  Token string(SourceLocation at) {
    advance();  // opening quote
    const std::size_t start = position_;
    while (position_ < source_.size() && source_[position_] != '"' && source_[position_] != '\n') {
      advance();
    }
    if (position_ >= source_.size() || source_[position_] != '"') {
      Token invalid{TokenKind::Invalid, source_.substr(start, position_ - start), at, {}};
      invalid.error = "unterminated string (strings end with '\"' on the same line)";
      return invalid;
    }
    Token token{TokenKind::String, source_.substr(start, position_ - start), at, {}};
    advance();  // closing quote
    return token;
  }

  std::string_view source_;
  std::size_t position_ = 0;
  std::uint32_t line_ = 1;
  std::uint32_t column_ = 1;
};

}  // namespace

std::vector<Token> tokenize(std::string_view source) {
  return Lexer(source).run();
}

std::string_view tokenKindName(TokenKind kind) {
  switch (kind) {
    case TokenKind::Identifier:
      return "a name";
    case TokenKind::Number:
      return "a number";
    case TokenKind::String:
      return "a string";
    case TokenKind::Less:
      return "'<'";
    case TokenKind::Greater:
      return "'>'";
    case TokenKind::Equals:
      return "'='";
    case TokenKind::LeftParen:
      return "'('";
    case TokenKind::RightParen:
      return "')'";
    case TokenKind::LeftBracket:
      return "'['";
    case TokenKind::RightBracket:
      return "']'";
    case TokenKind::Comma:
      return "','";
    case TokenKind::Semicolon:
      return "';'";
    case TokenKind::Invalid:
      return "an invalid character";
    case TokenKind::End:
      return "the end of the file";
  }
  return "?";
}

}  // namespace memograph::compiler
