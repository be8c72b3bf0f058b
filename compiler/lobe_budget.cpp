#include "compiler/lobe_budget.h"

#include <algorithm>
#include <bit>
#include <map>
#include <string>
#include <utility>

namespace memograph::compiler {

namespace {

// A ChooseShader node and its side (0: ChosenA, 1: ChosenB); {kRoot, 0} is every hit.
using Context = std::pair<std::size_t, std::size_t>;
constexpr std::size_t kRoot = static_cast<std::size_t>(-1);

const InputSource* input(const ResolvedNode& node, std::string_view socket) {
  const int index = node.type->socketIndex(socket);
  if (index < 0 || !node.inputs[std::size_t(index)])
    return nullptr;
  return &*node.inputs[std::size_t(index)];
}

// The context in which a weight input may be above 0: the innermost ChooseShader side it
// comes from through MixShader weights, or every hit.
Context contextOfWeight(const ResolvedGraph& graph, const InputSource* weight) {
  while (weight && weight->kind == InputSource::Kind::Link) {
    const ResolvedNode& producer = graph.nodes[weight->producer];
    const std::string& name = producer.type->name;
    if (name == "ChooseShader") {
      const int chosenB = producer.type->socketIndex("ChosenB");
      return {weight->producer, std::size_t(int(weight->producerSocket) == chosenB ? 1 : 0)};
    }
    if (name != "MixShader")
      break;
    weight = input(producer, "Weight");
  }
  return {kRoot, 0};
}

// Where a ChooseShader's own weights may be above 0: their common context, or every hit when
// they come from different ones (counted more often than they can be: never fewer).
Context contextOfChoice(const ResolvedGraph& graph, const ResolvedNode& choice) {
  const Context a = contextOfWeight(graph, input(choice, "WeightA"));
  const Context b = contextOfWeight(graph, input(choice, "WeightB"));
  return a == b ? a : Context{kRoot, 0};
}

// The lobes a sink adds (nodes/bsdf.inc): PrincipledLayers four, PrincipledBsdf one and one
// per Layers bit (all three where Layers is linked), every other sink one.
int lobesOf(const ResolvedNode& node) {
  const std::string& name = node.type->name;
  if (name == "PrincipledLayers")
    return 4;
  if (name != "PrincipledBsdf")
    return 1;
  const InputSource* layers = input(node, "Layers");
  if (!layers || layers->kind == InputSource::Kind::Link || layers->constant.components.size() != 1)
    return 4;
  const auto bits = static_cast<unsigned>(static_cast<long long>(layers->constant.components[0]));
  return 1 + std::popcount(bits & 7u);
}

bool writesLobes(const NodeType& type) {
  return std::find(type.outputsWritten.begin(), type.outputsWritten.end(), "lobes") !=
         type.outputsWritten.end();
}

bool writesPrincipledSet(const NodeType& type) {
  return type.name == "PrincipledBsdf" || type.name == "PrincipledOutput";
}

struct Budgets {
  std::map<Context, LobeBudget> direct;                  // the sinks of each context
  std::map<Context, std::vector<std::size_t>> children;  // its ChooseShaders

  LobeBudget of(const Context& context) const {
    LobeBudget total;
    if (auto it = direct.find(context); it != direct.end())
      total = it->second;
    if (auto it = children.find(context); it != children.end()) {
      for (const std::size_t choice : it->second) {
        const LobeBudget a = of({choice, 0});
        const LobeBudget b = of({choice, 1});
        total.lobes += std::max(a.lobes, b.lobes);
        total.principledSets += std::max(a.principledSets, b.principledSets);
      }
    }
    return total;
  }
};

}  // namespace

LobeBudget lobeBudget(const ResolvedGraph& graph, const std::vector<std::size_t>& order) {
  Budgets budgets;
  for (const std::size_t index : order) {
    const ResolvedNode& node = graph.nodes[index];
    if (node.type->name == "ChooseShader") {
      budgets.children[contextOfChoice(graph, node)].push_back(index);
      continue;
    }
    const bool lobes = writesLobes(*node.type);
    const bool principled = writesPrincipledSet(*node.type);
    if (!lobes && !principled)
      continue;
    // PrincipledOutput has no weight: every hit.
    const Context context = contextOfWeight(graph, input(node, "Weight"));
    LobeBudget& direct = budgets.direct[context];
    if (lobes)
      direct.lobes += lobesOf(node);
    if (principled)
      direct.principledSets += 1;
  }
  return budgets.of({kRoot, 0});
}

bool checkLobeBudget(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                     const SourceFile& file, Diagnostics& diagnostics) {
  const LobeBudget budget = lobeBudget(graph, order);
  if (budget.lobes <= kMaxLobes && budget.principledSets <= 1)
    return true;
  // The last sink is where the budget runs out, in the order the sinks run.
  const Node* last = nullptr;
  for (const std::size_t index : order)
    if (writesLobes(*graph.nodes[index].type) || writesPrincipledSet(*graph.nodes[index].type))
      last = graph.nodes[index].source;
  const SourceLocation where = last ? last->location : SourceLocation{};
  if (budget.lobes > kMaxLobes)
    diagnostics.error(file, where,
                      "the BSDF sinks can add " + std::to_string(budget.lobes) +
                          " lobes at one hit, more than the " + std::to_string(kMaxLobes) +
                          " a hit holds (the rest would be dropped): choose between shaders "
                          "per hit with ChooseShader so that no choice leaves more than " +
                          std::to_string(kMaxLobes));
  if (budget.principledSets > 1)
    diagnostics.error(file, where,
                      std::to_string(budget.principledSets) +
                          " Principled BSDFs (PrincipledOutput, PrincipledBsdf) can write the "
                          "Principled outputs at one hit, which hold one: choose between them "
                          "per hit with ChooseShader");
  return false;
}

}  // namespace memograph::compiler
