// The value types that flow along graph edges (thesis §5.1): plain scalars/vectors and their
// derivative-carrying `_D` twins, plus the context types that are not sockets.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace memograph::compiler {

// The two shading languages the compiler emits.
enum class Target { Glsl, Hlsl };

// Table: a constant lookup table of kTableEntries float4s (Cycles' ramp and curve tables,
// RAMP_TABLE_SIZE), bound only from a bracket literal; prelude `struct Table`.
enum class BaseType { Float, Float2, Float3, Float4, Int, TextureRef, Table, Inputs, Outputs };

inline constexpr int kTableEntries = 256;
inline constexpr int kTableNumbers = kTableEntries * 4;

struct Type {
  BaseType base = BaseType::Float;
  bool derivatives = false;  // a `_D` type: value plus two footprint derivatives

  bool operator==(const Type&) const = default;
  auto operator<=>(const Type&) const = default;

  // Number of float components for Float..Float4, else 0. Inline: overload selection asks
  // it for every candidate pair.
  int width() const {
    switch (base) {
      case BaseType::Float:
        return 1;
      case BaseType::Float2:
        return 2;
      case BaseType::Float3:
        return 3;
      case BaseType::Float4:
        return 4;
      default:
        return 0;
    }
  }
  bool isFloat() const { return width() > 0; }
  bool isContext() const { return base == BaseType::Inputs || base == BaseType::Outputs; }
  // The spelling in shader code: "float3", "float3_D", "int", "TextureRef", "Table",
  // "MaterialInputs".
  std::string name() const;

  static std::optional<Type> parse(std::string_view spelling);
  static Type floatOfWidth(int width, bool derivatives);
};

}  // namespace memograph::compiler
