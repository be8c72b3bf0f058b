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

}  // namespace

void Lexer::advance() {
  if (source_[position_] == '\n') {
    ++line_;
    column_ = 1;
  } else {
    ++column_;
  }
  ++position_;
}

void Lexer::skipSpaceAndComments() {
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

Token Lexer::make(TokenKind kind, std::size_t start, SourceLocation at) const {
  return Token{kind, source_.substr(start, position_ - start), at};
}

Token Lexer::next() {
  skipSpaceAndComments();
  const SourceLocation at = here();
  if (position_ >= source_.size())
    return Token{TokenKind::End, {}, at};
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
  return single(TokenKind::Invalid);
}

// -?digits[.digits][e[+-]digits]; validity of the value is checked by the parser.
Token Lexer::number(std::size_t start, SourceLocation at) {
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

Token Lexer::string(SourceLocation at) {
  const std::size_t quote = position_;
  advance();  // opening quote
  const std::size_t start = position_;
  while (position_ < source_.size() && source_[position_] != '"' && source_[position_] != '\n') {
    advance();
  }
  if (position_ >= source_.size() || source_[position_] != '"')
    return make(TokenKind::Invalid, quote, at);
  Token token = make(TokenKind::String, start, at);
  advance();  // closing quote
  return token;
}

std::vector<Token> tokenize(std::string_view source) {
  Lexer lexer(source);
  std::vector<Token> tokens;
  do {
    tokens.push_back(lexer.next());
  } while (tokens.back().kind != TokenKind::End);
  return tokens;
}

std::string invalidTokenMessage(const Token& token) {
  if (token.text.empty())
    return "unexpected end of the file";
  if (token.text.front() == '"')
    return "unterminated string (strings end with '\"' on the same line)";
  const auto byte = static_cast<unsigned char>(token.text.front());
  if (std::isprint(byte))
    return std::string("unexpected character '") + token.text.front() + "'";
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", byte);
  return std::string("unexpected byte ") + hex;
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
