#include "compiler/conversions.h"

namespace memograph::compiler {

std::optional<Cost> conversionCost(Type from, Type to) {
  if (from == to)
    return Cost{};
  if (from.base == BaseType::Int && to.isFloat() && !to.derivatives) {
    Cost cost;
    // int → float is exact; to a vector it is also a splat.
    (to.width() == 1 ? cost.intToFloat : cost.conversions) = 1;
    return cost;
  }
  if (!from.isFloat() || !to.isFloat())
    return std::nullopt;
  if (!from.derivatives && to.derivatives)
    return std::nullopt;
  Cost cost;
  if (from.width() != to.width())
    cost.conversions = 1;
  if (from.width() > to.width())
    cost.truncations = 1;
  if (from.derivatives && !to.derivatives)
    cost.droppedDerivatives = 1;
  return cost;
}

std::string convertExpression(const std::string& expression, Type from, Type to) {
  if (from == to)
    return expression;
  std::string value = expression;
  if (from.derivatives && !to.derivatives) {
    value = "mg_drop_D(" + value + ")";
    from.derivatives = false;
  }
  if (from == to)
    return value;
  return "mg_to_" + to.name() + "(" + value + ")";
}

}  // namespace memograph::compiler
