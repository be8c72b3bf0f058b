// Splits .mgraph text into tokens (grammar in docs/guide/graph-format.md). Never fails: bytes it
// cannot read become Invalid tokens, which the parser reports. The parser pulls tokens one at a
// time (Lexer::next), so a 16 MiB graph never holds millions of tokens at once.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/source_file.h"

namespace memograph::compiler {

enum class TokenKind {
  Identifier,
  Number,
  String,
  Less,          // <
  Greater,       // >
  Equals,        // =
  LeftParen,     // (
  RightParen,    // )
  LeftBracket,   // [
  RightBracket,  // ]
  Comma,
  Semicolon,
  Invalid,  // an unexpected byte, or an unterminated string
  End,
};

// 32 bytes, no heap: a token is a view into the source, and an Invalid token's message is
// derived from its text (invalidTokenMessage) only when it is reported.
struct Token {
  TokenKind kind = TokenKind::End;
  // The token's bytes in the source. String: without quotes. Invalid: the unexpected byte,
  // or an unterminated string from its opening quote to the end of the line.
  std::string_view text;
  SourceLocation location;
};

class Lexer {
 public:
  explicit Lexer(std::string_view source) : source_(source) {}

  // The next token; End at the end of the source, and End again on every later call.
  Token next();

 private:
  SourceLocation here() const { return {line_, column_}; }
  void advance();
  void skipSpaceAndComments();
  Token make(TokenKind kind, std::size_t start, SourceLocation at) const;
  Token number(std::size_t start, SourceLocation at);
  Token string(SourceLocation at);

  std::string_view source_;
  std::size_t position_ = 0;
  std::uint32_t line_ = 1;
  std::uint32_t column_ = 1;
};

// Every token of a short text, End last (literals in node libraries, tests).
std::vector<Token> tokenize(std::string_view source);

// What is wrong with an Invalid token: "unexpected character '@'", "unexpected byte 0x01",
// "unterminated string …".
std::string invalidTokenMessage(const Token& token);

std::string_view tokenKindName(TokenKind kind);

}  // namespace memograph::compiler
