// Implicit conversions between edge types (thesis §5.1, "Convert" in Listing 5.3), each
// emitted as a call to a named function of the prelude, and what they cost for overload
// selection.
#pragma once

#include <optional>
#include <string>

#include "compiler/types.h"

namespace memograph::compiler {

// Overload-selection cost, compared lexicographically: fewest conversions first; among
// those, fewest that lose information (truncating a vector), so a scalar is splatted rather
// than a vector cut down (Listing 5.1 → 5.3 picks float3 Mul/Add this way); then the fewest
// lost derivatives (a value that varies over the footprint entering a plain socket of a node
// whose outputs carry derivatives: they would be incomplete), so derivatives reach every
// socket that has a `_D` overload; then the least derivative work, so derivatives flow only
// where a consumer needs them; then the fewest dropped derivatives; then the fewest `int` →
// `float` conversions (exact, so ranked below derivative work: an IntConstant feeds a float
// socket through its plain overload, not its `_D` one); last, the narrowest types (the least
// arithmetic: a float2 graph extended to float3 at its end beats a float3 graph fed an
// extended float2).
struct Cost {
  int conversions = 0;
  int truncations = 0;
  int lostDerivatives = 0;
  int derivativeWork = 0;
  int droppedDerivatives = 0;
  int intToFloat = 0;
  int componentWidth = 0;  // sum of the chosen overloads' socket widths

  Cost operator+(const Cost& o) const {
    return {conversions + o.conversions,
            truncations + o.truncations,
            lostDerivatives + o.lostDerivatives,
            derivativeWork + o.derivativeWork,
            droppedDerivatives + o.droppedDerivatives,
            intToFloat + o.intToFloat,
            componentWidth + o.componentWidth};
  }
  auto operator<=>(const Cost&) const = default;
};

// The cost of passing a value of type `from` where `to` is expected, or nothing when no
// implicit conversion exists (plain → `_D` never does: derivatives cannot be invented).
std::optional<Cost> conversionCost(Type from, Type to);

// Shader code converting `expression` from `from` to `to` (must be convertible):
// "mg_to_float3(link0)", "mg_to_float(mg_drop_D(link4))", or `expression` itself.
std::string convertExpression(const std::string& expression, Type from, Type to);

}  // namespace memograph::compiler
