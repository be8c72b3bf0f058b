// Splits .mgraph text into tokens (grammar in docs/guide/graph-format.md). Never fails: bytes it
// cannot read become Invalid tokens, which the parser reports.
#pragma once

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

struct Token {
  TokenKind kind = TokenKind::End;
  std::string_view text;  // the token's bytes in the source (for String: without quotes)
  SourceLocation location;
  std::string error;  // Invalid: what is wrong
};

std::vector<Token> tokenize(std::string_view source);

std::string_view tokenKindName(TokenKind kind);

}  // namespace memograph::compiler
