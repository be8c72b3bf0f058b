// Literals shared by graphs and `@default` annotations: parsing from text and printing as
// shader code of a given type.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "compiler/graph.h"
#include "compiler/types.h"

namespace memograph::compiler {

// Parses "0.5", "-2", "(1, 0, 0)"; nothing for anything else.
std::optional<Literal> parseLiteral(std::string_view text);

// Whether the literal is a whole number a shader `int` (32 bits in GLSL and HLSL) holds.
bool isShaderInt(const Literal& literal);

// The literal's own type: a Number is float (int when written as a whole number), a Tuple
// floatN, a String a TextureRef.
Type literalType(const Literal& literal);

// Shortest round-trip spelling that is a float literal in both languages: "0.5", "1.0",
// "1e-07" becomes "1e-07" (valid in both).
std::string formatFloat(double value);

// Shader code for a plain constant of `type` (float or floatN or int). Scalars splat to all
// components; tuples must match the width.
std::string formatConstant(const Literal& literal, Type type);

// Component i of a constant written to a socket of several components: a number splat to
// every component; a shorter vector padded with 0, and with 1 for the fourth (alpha).
double literalComponent(const Literal& literal, int i);

}  // namespace memograph::compiler
