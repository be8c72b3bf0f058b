#include "compiler/literal.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

#include "compiler/diagnostics.h"
#include "compiler/lexer.h"

namespace memograph::compiler {

std::optional<Literal> parseLiteral(std::string_view text) {
  const auto tokens = tokenize(text);
  auto number = [](const Token& token, double& value) {
    const std::string s(token.text);
    const char* begin = s.c_str() + (s[0] == '+' ? 1 : 0);
    const auto [rest, status] = std::from_chars(begin, s.c_str() + s.size(), value);
    return status == std::errc() && rest == s.c_str() + s.size() && std::isfinite(value);
  };
  Literal literal;
  if (tokens.size() == 2 && tokens[0].kind == TokenKind::Number) {
    double value = 0;
    if (!number(tokens[0], value))
      return std::nullopt;
    literal.components = {value};
    literal.isInteger = tokens[0].text.find_first_of(".eE") == std::string_view::npos;
    return literal;
  }
  // ( n , n [, n [, n]] ) End
  if (tokens.size() < 6 || tokens.front().kind != TokenKind::LeftParen)
    return std::nullopt;
  literal.kind = Literal::Kind::Tuple;
  std::size_t i = 1;
  while (true) {
    double value = 0;
    if (tokens[i].kind != TokenKind::Number || !number(tokens[i], value))
      return std::nullopt;
    literal.components.push_back(value);
    ++i;
    if (tokens[i].kind == TokenKind::Comma) {
      ++i;
      continue;
    }
    if (tokens[i].kind == TokenKind::RightParen && tokens[i + 1].kind == TokenKind::End)
      break;
    return std::nullopt;
  }
  if (literal.components.size() > 4)
    return std::nullopt;
  return literal;
}

bool isShaderInt(const Literal& literal) {
  if (literal.kind != Literal::Kind::Number || !literal.isInteger)
    return false;
  const double value = literal.components.at(0);
  return value >= std::numeric_limits<std::int32_t>::min() &&
         value <= std::numeric_limits<std::int32_t>::max();
}

Type literalType(const Literal& literal) {
  switch (literal.kind) {
    case Literal::Kind::String:
      return Type{BaseType::TextureRef, false};
    case Literal::Kind::Table:
      return Type{BaseType::Table, false};
    case Literal::Kind::Tuple:
      return Type::floatOfWidth(static_cast<int>(literal.components.size()), false);
    case Literal::Kind::Number:
      break;
  }
  return Type{literal.isInteger ? BaseType::Int : BaseType::Float, false};
}

std::string formatFloat(double value) {
  const auto f = static_cast<float>(value);  // shaders compute in 32-bit floats
  char buffer[64];
  const auto [end, status] = std::to_chars(buffer, buffer + sizeof buffer, f);
  std::string text(buffer, end);
  if (text.find_first_of(".e") == std::string::npos)
    text += ".0";
  if (text == "-0.0")
    text = "0.0";
  return text;
}

std::string formatConstant(const Literal& literal, Type type) {
  if (type.base == BaseType::Int) {
    return std::to_string(static_cast<long long>(std::llround(literal.components.at(0))));
  }
  const int width = type.width();
  if (width == 1)
    return formatFloat(literal.components.at(0));
  std::string code = type.name() + "(";
  for (int i = 0; i < width; ++i)
    code += (i > 0 ? ", " : "") + formatFloat(literalComponent(literal, i));
  return code + ")";
}

double literalComponent(const Literal& literal, int i) {
  const auto index = static_cast<std::size_t>(i);
  if (literal.components.size() == 1)
    return literal.components[0];
  return index < literal.components.size() ? literal.components[index] : (i == 3 ? 1.0 : 0.0);
}

}  // namespace memograph::compiler
