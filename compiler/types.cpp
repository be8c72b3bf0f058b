#include "compiler/types.h"

#include <array>
#include <utility>

namespace memograph::compiler {

namespace {
constexpr std::array<std::pair<std::string_view, BaseType>, 9> kSpellings{{
    {"float", BaseType::Float},
    {"float2", BaseType::Float2},
    {"float3", BaseType::Float3},
    {"float4", BaseType::Float4},
    {"int", BaseType::Int},
    {"TextureRef", BaseType::TextureRef},
    {"Table", BaseType::Table},
    {"MaterialInputs", BaseType::Inputs},
    {"MaterialOutputs", BaseType::Outputs},
}};
}  // namespace

std::string Type::name() const {
  for (const auto& [spelling, b] : kSpellings) {
    if (b == base)
      return std::string(spelling) + (derivatives ? "_D" : "");
  }
  return "?";
}

std::optional<Type> Type::parse(std::string_view spelling) {
  bool derivatives = false;
  if (spelling.ends_with("_D")) {
    derivatives = true;
    spelling.remove_suffix(2);
  }
  for (const auto& [candidate, base] : kSpellings) {
    if (candidate != spelling)
      continue;
    Type type{base, derivatives};
    if (derivatives && !type.isFloat())
      return std::nullopt;
    return type;
  }
  return std::nullopt;
}

Type Type::floatOfWidth(int width, bool derivatives) {
  constexpr BaseType kByWidth[] = {BaseType::Float, BaseType::Float2, BaseType::Float3,
                                   BaseType::Float4};
  return Type{kByWidth[width - 1], derivatives};
}

}  // namespace memograph::compiler
