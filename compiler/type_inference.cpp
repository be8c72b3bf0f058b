#include "compiler/type_inference.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <set>

#include "compiler/conversions.h"
#include "compiler/literal.h"
#include "compiler/material_interface.h"

namespace memograph::compiler {

std::optional<Cost> constantCost(const Literal& value, Type to) {
  switch (value.kind) {
    case Literal::Kind::String:
      return to.base == BaseType::TextureRef ? std::optional(Cost{}) : std::nullopt;
    case Literal::Kind::Table:
      return to.base == BaseType::Table ? std::optional(Cost{}) : std::nullopt;
    case Literal::Kind::Number:
      if (to.base == BaseType::Int)
        return isShaderInt(value) ? std::optional(Cost{}) : std::nullopt;
      return to.isFloat() ? std::optional(Cost{}) : std::nullopt;  // a scalar splats freely
    case Literal::Kind::Tuple:
      if (!to.isFloat())
        return std::nullopt;
      {
        const int width = static_cast<int>(value.components.size());
        Cost cost;
        cost.conversions = width == to.width() ? 0 : 1;
        cost.truncations = width > to.width() ? 1 : 0;
        return cost;
      }
  }
  return std::nullopt;
}

std::string overloadSignature(const NodeType& type, const Overload& overload) {
  std::string inputs, outputs;
  for (std::size_t i = 0; i < type.sockets.size(); ++i) {
    auto& list = type.sockets[i].direction == Direction::In ? inputs : outputs;
    list +=
        (list.empty() ? "" : ", ") + overload.socketTypes[i].name() + " " + type.sockets[i].name;
  }
  return type.name + "(" + inputs + ")" + (outputs.empty() ? "" : " -> " + outputs);
}

namespace {

struct Edge {
  std::size_t producer, producerSocket, consumer, consumerSocket;
};

// The distinct types one socket takes over a node's candidate overloads, one bit per Type.
// revise() builds two of these per edge and pass; as std::set their allocations were most
// of the time spent compiling a large graph.
class TypeSet {
 public:
  void insert(Type type) { bits_ |= bit(type); }

  template <typename Predicate>
  bool anyOf(Predicate predicate) const {
    for (unsigned i = 0; i < kTypeCount; ++i) {
      if ((bits_ >> i & 1u) && predicate(typeAt(i)))
        return true;
    }
    return false;
  }

  // In Type's order, for messages.
  std::set<Type> toSet() const {
    std::set<Type> types;
    anyOf([&](Type type) {
      types.insert(type);
      return false;
    });
    return types;
  }

 private:
  static constexpr unsigned kBaseTypeCount = static_cast<unsigned>(BaseType::Outputs) + 1;
  static constexpr unsigned kTypeCount = 2 * kBaseTypeCount;
  static_assert(kTypeCount <= 32, "TypeSet holds its bits in 32 bits");

  static std::uint32_t bit(Type type) {
    return static_cast<std::uint32_t>(
        1u << (2 * static_cast<unsigned>(type.base) + (type.derivatives ? 1 : 0)));
  }
  static Type typeAt(unsigned i) { return Type{static_cast<BaseType>(i / 2), i % 2 == 1}; }

  std::uint32_t bits_ = 0;
};

std::string joinTypes(const std::set<Type>& types) {
  std::string text;
  for (const auto& t : types)
    text += (text.empty() ? "" : ", ") + t.name();
  return text;
}

class Inference {
 public:
  Inference(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
            const SourceFile& file, Diagnostics& diagnostics)
      : graph_(graph), order_(order), file_(file), diagnostics_(diagnostics) {}

  std::optional<OverloadChoice> run() {
    candidates_.resize(graph_.nodes.size());
    for (const std::size_t node : order_) {
      if (!initialCandidates(node))
        return std::nullopt;
    }
    for (const std::size_t consumer : order_) {
      const auto& inputs = graph_.nodes[consumer].inputs;
      for (std::size_t s = 0; s < inputs.size(); ++s) {
        if (inputs[s] && inputs[s]->kind == InputSource::Kind::Link) {
          edges_.push_back({inputs[s]->producer, inputs[s]->producerSocket, consumer, s});
        }
      }
    }
    // Phases 1 and 2 alternate until nothing changes: phase 1 walks the edges from the
    // sinks towards the sources, phase 2 the other way.
    for (bool changed = true; changed;) {
      changed = false;
      for (auto e = edges_.rbegin(); e != edges_.rend(); ++e) {
        if (!revise(*e, changed))
          return std::nullopt;
      }
      for (const auto& e : edges_) {
        if (!revise(e, changed))
          return std::nullopt;
      }
    }
    computeVarying();
    auto chosen = choose();
    if (chosen)
      warnAboutLostDerivatives(*chosen);
    return chosen;
  }

 private:
  const Overload& overload(std::size_t node, std::size_t k) const {
    return graph_.nodes[node].type->overloads[k];
  }
  Type socketType(std::size_t node, std::size_t k, std::size_t socket) const {
    return overload(node, k).socketTypes[socket];
  }

  bool initialCandidates(std::size_t node) {
    const auto& resolved = graph_.nodes[node];
    for (std::size_t k = 0; k < resolved.type->overloads.size(); ++k) {
      // Its derivatives would be made up (zeros for a value that varies): never chosen.
      if (resolved.type->overloads[k].inventsDerivatives)
        continue;
      bool fits = true;
      for (std::size_t s = 0; s < resolved.inputs.size() && fits; ++s) {
        const auto& input = resolved.inputs[s];
        if (input && input->kind != InputSource::Kind::Link) {
          fits = constantCost(input->constant, socketType(node, k, s)).has_value();
        }
      }
      if (fits)
        candidates_[node].push_back(k);
    }
    if (!candidates_[node].empty())
      return true;
    auto& d = diagnostics_.error(
        file_, resolved.source->location,
        "no overload of '" + resolved.type->name + "' accepts the constants given to it");
    for (const auto& o : resolved.type->overloads) {
      d.notes.push_back("candidate: " + overloadSignature(*resolved.type, o));
    }
    return false;
  }

  // Arc consistency on one edge: keep only overloads with a partner across it.
  bool revise(const Edge& e, bool& changed) {
    auto& producers = candidates_[e.producer];
    auto& consumers = candidates_[e.consumer];
    const auto offeredBefore = offeredTypes(e);
    const auto wantedBefore = wantedTypes(e);
    auto keepConsumer = [&](std::size_t k) {
      const Type to = socketType(e.consumer, k, e.consumerSocket);
      return offeredBefore.anyOf([&](Type from) { return conversionCost(from, to).has_value(); });
    };
    auto keepProducer = [&](std::size_t k) {
      const Type from = socketType(e.producer, k, e.producerSocket);
      return wantedBefore.anyOf([&](Type to) { return conversionCost(from, to).has_value(); });
    };
    const auto before = producers.size() + consumers.size();
    std::erase_if(consumers, [&](std::size_t k) { return !keepConsumer(k); });
    std::erase_if(producers, [&](std::size_t k) { return !keepProducer(k); });
    if (producers.size() + consumers.size() != before)
      changed = true;
    if (!producers.empty() && !consumers.empty())
      return true;
    reportMismatch(e, offeredBefore.toSet(), wantedBefore.toSet());
    return false;
  }

  TypeSet offeredTypes(const Edge& e) const {
    TypeSet types;
    for (const auto k : candidates_[e.producer]) {
      types.insert(socketType(e.producer, k, e.producerSocket));
    }
    return types;
  }
  TypeSet wantedTypes(const Edge& e) const {
    TypeSet types;
    for (const auto k : candidates_[e.consumer]) {
      types.insert(socketType(e.consumer, k, e.consumerSocket));
    }
    return types;
  }

  std::string socketName(std::size_t node, std::size_t socket) const {
    return graph_.nodes[node].type->sockets[socket].name;
  }
  std::string nodeName(std::size_t node) const { return graph_.nodes[node].type->name; }
  std::string where(std::size_t node) const {
    const auto at = graph_.nodes[node].source->location;
    return file_.path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column);
  }

  // A node that differentiates an input (takes it only as `_D`) but cannot give its own
  // output derivatives: feeding that output to a `_D` consumer needs a second derivative.
  bool differentiatesWithoutDerivativeOutput(std::size_t node, std::size_t socket) const {
    const NodeType& type = *graph_.nodes[node].type;
    bool takesD = false;
    for (const auto& o : type.overloads) {
      if (o.socketTypes[socket].derivatives)
        return false;
      takesD = takesD || o.derivativeInputs > 0;
    }
    return takesD;
  }

  void reportMismatch(const Edge& e, const std::set<Type>& offered, const std::set<Type>& wanted) {
    const auto& input = *graph_.nodes[e.consumer].inputs[e.consumerSocket];
    const bool allWantDerivatives =
        std::all_of(wanted.begin(), wanted.end(), [](Type t) { return t.derivatives; });
    const bool noneOfferDerivatives =
        std::none_of(offered.begin(), offered.end(), [](Type t) { return t.derivatives; });
    if (allWantDerivatives && noneOfferDerivatives &&
        differentiatesWithoutDerivativeOutput(e.producer, e.producerSocket)) {
      auto& d = diagnostics_.error(
          file_, input.location,
          "'" + nodeName(e.consumer) + "' needs derivatives of its input '" +
              socketName(e.consumer, e.consumerSocket) + "', but '" + nodeName(e.producer) +
              "' computes its output from derivatives already: that would need a second "
              "derivative, which memograph cannot generate (thesis §5.1)");
      d.notes.push_back("path: " + derivativePath(e));
      d.notes.push_back("feed '" + socketName(e.consumer, e.consumerSocket) +
                        "' from a value that does not go through '" + nodeName(e.producer) + "'");
      return;
    }
    if (allWantDerivatives && noneOfferDerivatives) {
      if (const auto path = pathToInventedDerivatives(e)) {
        const std::size_t source = path->back();
        std::string members;
        for (const auto& member : graph_.nodes[source].type->inputsRead)
          members += (members.empty() ? "'" : ", '") + member + "'";
        auto& d = diagnostics_.error(
            file_, input.location,
            "'" + nodeName(e.consumer) + "' needs derivatives of its input '" +
                socketName(e.consumer, e.consumerSocket) + "', but they would come from '" +
                nodeName(source) + "' (" + where(source) + "), which reads " + members +
                ": MaterialInputs carries no derivatives of it, and memograph never invents "
                "them (docs/guide/graph-format.md, Derivatives)");
        std::string text = "'" + nodeName(e.consumer) + "' (" + where(e.consumer) + ")";
        for (const std::size_t node : *path)
          text += " ← '" + nodeName(node) + "' (" + where(node) + ")";
        d.notes.push_back("path: " + text);
        d.notes.push_back("feed '" + socketName(e.consumer, e.consumerSocket) +
                          "' from values with derivatives (UVInput, PositionInput, …), or "
                          "from ones that do not go through '" +
                          nodeName(source) + "'");
        return;
      }
    }
    auto& d = diagnostics_.error(file_, input.location,
                                 "no overload of '" + nodeName(e.consumer) +
                                     "' fits what arrives at input '" +
                                     socketName(e.consumer, e.consumerSocket) + "'");
    d.notes.push_back("link " + std::to_string(input.link) + " from '" + nodeName(e.producer) +
                      "' (" + where(e.producer) + ") can be: " + joinTypes(offered));
    d.notes.push_back(std::string("'").append(nodeName(e.consumer)) +
                      "' could take: " + joinTypes(wanted));
    if (allWantDerivatives && noneOfferDerivatives) {
      d.notes.push_back("derivatives (_D types) cannot be made from a value without them");
    }
  }

  // consumer ← producer ← … ← the source whose derivatives the producer differentiates.
  std::string derivativePath(const Edge& e) const {
    // Appending (rather than "'" + …) also sidesteps a GCC 12 -Wrestrict false positive.
    auto describe = [&](std::size_t node) {
      std::string text;
      text.append("'").append(nodeName(node)).append("' (").append(where(node)).append(")");
      return text;
    };
    std::string path = describe(e.consumer) + " ← " + describe(e.producer);
    std::size_t node = e.producer;
    for (std::size_t steps = 0; steps < 64; ++steps) {
      const auto& inputs = graph_.nodes[node].inputs;
      const InputSource* next = nullptr;
      for (const auto& input : inputs) {
        if (input && input->kind == InputSource::Kind::Link) {
          next = &*input;
          break;
        }
      }
      if (!next)
        break;
      node = next->producer;
      path += " ← " + describe(node);
    }
    return path;
  }

  // The producers from e.producer up to a node whose only `_D` overloads would invent
  // derivatives (and so were never candidates), following links that offer no `_D` type;
  // nothing when there is none within 64 steps.
  std::optional<std::vector<std::size_t>> pathToInventedDerivatives(const Edge& e) const {
    std::vector<std::size_t> path{e.producer};
    std::vector<char> seen(graph_.nodes.size(), 0);
    // Depth-first, through inputs in socket order: the first such source found.
    std::function<bool(std::size_t, int)> search = [&](std::size_t node, int depth) -> bool {
      if (seen[node] || depth > 64)
        return false;
      seen[node] = 1;
      const auto& overloads = graph_.nodes[node].type->overloads;
      if (std::any_of(overloads.begin(), overloads.end(),
                      [](const Overload& o) { return o.inventsDerivatives; })) {
        return true;
      }
      for (const auto& input : graph_.nodes[node].inputs) {
        if (!input || input->kind != InputSource::Kind::Link)
          continue;
        path.push_back(input->producer);
        if (search(input->producer, depth + 1))
          return true;
        path.pop_back();
      }
      return false;
    };
    if (search(e.producer, 0))
      return path;
    return std::nullopt;
  }

  // Whether a node's outputs vary over a pixel's footprint: it reads a MaterialInputs member
  // that does (all but the per-object or per-frame ones, and the path state, which is one
  // ray's: its ray length too, whose derivatives Cycles' bump also takes as zero, as it
  // offsets the position and not the ray), or a linked input varies.
  void computeVarying() {
    varies_.assign(graph_.nodes.size(), 0);
    for (const std::size_t node : order_) {
      const auto& resolved = graph_.nodes[node];
      for (const auto& member : resolved.type->inputsRead) {
        const bool constantOverFootprint = member == "time" || member == "objectLocation" ||
                                           member == "objectRandom" || member == "backfacing" ||
                                           isPathInput(member);
        if (!constantOverFootprint) {
          varies_[node] = 1;
        }
      }
      for (const auto& input : resolved.inputs) {
        if (input && input->kind == InputSource::Kind::Link && varies_[input->producer])
          varies_[node] = 1;
      }
    }
  }

  // The cost of edge producer (overload kp) → consumer (overload kc): the conversion, and a
  // lost derivative when a varying value enters a plain socket of an overload with `_D`
  // outputs (their derivatives then miss how that input varies).
  std::optional<Cost> edgeCost(std::size_t producer, std::size_t kp, std::size_t producerSocket,
                               std::size_t consumer, std::size_t kc,
                               std::size_t consumerSocket) const {
    const Type to = socketType(consumer, kc, consumerSocket);
    auto cost = conversionCost(socketType(producer, kp, producerSocket), to);
    if (cost && loses(producer, consumer, kc, to))
      cost->lostDerivatives = 1;
    return cost;
  }
  bool loses(std::size_t producer, std::size_t consumer, std::size_t kc, Type to) const {
    return varies_[producer] && to.isFloat() && !to.derivatives &&
           overload(consumer, kc).derivativeOutputs > 0;
  }

  // The node downstream of `node` that needs its derivatives: follow outputs taken as `_D`
  // to a node that takes derivatives but gives none on (a texture lookup, a bump). Nothing
  // when no consumer takes `node`'s derivatives.
  std::optional<std::size_t> derivativeConsumer(std::size_t node,
                                                const OverloadChoice& chosen) const {
    std::optional<std::size_t> found;
    for (int steps = 0; steps < 64; ++steps) {
      std::optional<std::size_t> next;
      const auto& consumers = graph_.nodes[node].consumers;
      for (std::size_t socket = 0; socket < consumers.size() && !next; ++socket) {
        if (!socketType(node, *chosen[node], socket).derivatives)
          continue;
        for (const auto& consumer : consumers[socket]) {
          if (chosen[consumer.node] &&
              socketType(consumer.node, *chosen[consumer.node], consumer.socket).derivatives) {
            next = consumer.node;
            break;
          }
        }
      }
      if (!next)
        return found;
      found = node = *next;
    }
    return found;
  }

  // Warns where a value that varies reaches a plain socket of a node whose derivatives a
  // consumer needs: those derivatives leave out how the input varies (the socket has no
  // `_D` overload that fits; the cost order takes one whenever it does).
  void warnAboutLostDerivatives(const OverloadChoice& chosen) {
    for (const std::size_t node : order_) {
      const std::size_t k = *chosen[node];
      if (overload(node, k).derivativeOutputs == 0)
        continue;
      const auto& inputs = graph_.nodes[node].inputs;
      std::optional<std::size_t> needer;
      bool looked = false;
      for (std::size_t s = 0; s < inputs.size(); ++s) {
        if (!inputs[s] || inputs[s]->kind != InputSource::Kind::Link ||
            !loses(inputs[s]->producer, node, k, socketType(node, k, s))) {
          continue;
        }
        if (!looked) {
          needer = derivativeConsumer(node, chosen);
          looked = true;
        }
        if (!needer)
          break;
        const std::size_t producer = inputs[s]->producer;
        const Type produced = socketType(producer, *chosen[producer], inputs[s]->producerSocket);
        auto& d = diagnostics_.warning(
            file_, inputs[s]->location,
            "the derivatives of '" + nodeName(node) + "' leave out how its input '" +
                socketName(node, s) + "' varies: '" + nodeName(node) +
                "' has no derivative (_D) overload for it, and '" + nodeName(*needer) + "' (" +
                where(*needer) + ") needs those derivatives");
        d.notes.push_back(std::string("link ") + std::to_string(inputs[s]->link) + " from '" +
                          nodeName(producer) + "' (" + where(producer) + ") varies over the " +
                          "pixel footprint" +
                          (produced.derivatives ? "; its derivatives are dropped here" : ""));
        d.notes.push_back("filtering downstream sees only the other inputs' derivatives; give '" +
                          socketName(node, s) + "' a constant to silence this");
      }
    }
  }

  Cost ownCost(std::size_t node, std::size_t k) const {
    const auto& o = overload(node, k);
    Cost cost;
    cost.derivativeWork = o.derivativeInputs + o.derivativeOutputs;
    for (const Type& type : o.socketTypes)
      cost.componentWidth += type.width();
    const auto& inputs = graph_.nodes[node].inputs;
    for (std::size_t s = 0; s < inputs.size(); ++s) {
      if (inputs[s] && inputs[s]->kind != InputSource::Kind::Link) {
        cost = cost + *constantCost(inputs[s]->constant, socketType(node, k, s));
      }
    }
    return cost;
  }

  // Phase 3. A dynamic programme over the remaining overloads: best[n][k] is the cheapest
  // cost of node n's inputs' subgraphs when n takes overload k (exact on trees; shared
  // subgraphs are counted once per consumer). Then, from the sinks back, each node takes the
  // overload cheapest for its chosen consumers. Equal costs are an ambiguity.
  std::optional<OverloadChoice> choose() {
    std::vector<std::vector<Cost>> best(graph_.nodes.size());
    for (const std::size_t node : order_) {
      best[node].reserve(candidates_[node].size());
      for (const std::size_t k : candidates_[node]) {
        Cost total = ownCost(node, k);
        const auto& inputs = graph_.nodes[node].inputs;
        for (std::size_t s = 0; s < inputs.size(); ++s) {
          if (!inputs[s] || inputs[s]->kind != InputSource::Kind::Link)
            continue;
          const std::size_t p = inputs[s]->producer;
          std::optional<Cost> cheapest;
          for (std::size_t i = 0; i < candidates_[p].size(); ++i) {
            const auto conversion =
                edgeCost(p, candidates_[p][i], inputs[s]->producerSocket, node, k, s);
            if (!conversion)
              continue;
            const Cost c = best[p][i] + *conversion;
            if (!cheapest || c < *cheapest)
              cheapest = c;
          }
          total = total + cheapest.value_or(Cost{.conversions = 1 << 20});
        }
        best[node].push_back(total);
      }
    }
    OverloadChoice chosen(graph_.nodes.size());
    for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
      const std::size_t node = *it;
      std::optional<Cost> bestCost;
      std::vector<std::size_t> tied;
      for (std::size_t i = 0; i < candidates_[node].size(); ++i) {
        const std::size_t k = candidates_[node][i];
        std::optional<Cost> total = best[node][i];
        for (std::size_t socket = 0; socket < graph_.nodes[node].consumers.size() && total;
             ++socket) {
          for (const auto& consumer : graph_.nodes[node].consumers[socket]) {
            if (!chosen[consumer.node])
              continue;  // pruned consumer
            const auto conversion =
                edgeCost(node, k, socket, consumer.node, *chosen[consumer.node], consumer.socket);
            if (!conversion) {
              total.reset();
              break;
            }
            *total = *total + *conversion;
          }
        }
        if (!total)
          continue;
        if (!bestCost || *total < *bestCost) {
          bestCost = total;
          tied = {k};
        } else if (*total == *bestCost) {
          tied.push_back(k);
        }
      }
      if (tied.size() != 1) {
        // The greedy pass is exact on trees only: where nodes are shared, search every
        // combination before reporting.
        const auto search = exhaustiveSearch();
        if (search.best && !search.tie)
          return search.best;
        if (tied.empty() && !search.gaveUp && search.tie) {
          reportAmbiguity(search.tieNode,
                          {*(*search.best)[search.tieNode], *(*search.tie)[search.tieNode]});
          return std::nullopt;
        }
        if (tied.empty()) {
          auto& d = diagnostics_.error(
              file_, graph_.nodes[node].source->location,
              "no overload of '" + nodeName(node) + "' fits all the nodes its outputs feed");
          for (const auto k : candidates_[node]) {
            d.notes.push_back("candidate: " +
                              overloadSignature(*graph_.nodes[node].type, overload(node, k)));
          }
        } else {
          reportAmbiguity(node, tied);
        }
        if (search.gaveUp) {
          diagnostics_.last().notes.push_back(
              "type inference gave up its exhaustive search after " +
              std::to_string(kMaxSearchSteps) +
              " overload combinations (docs/guide/graph-format.md); a valid choice may exist: "
              "make some types explicit, e.g. with Separate/Combine or constants");
        }
        return std::nullopt;
      }
      chosen[node] = tied.front();
    }
    return chosen;
  }

  // The search's bound: overloads tried (partial assignments), all nodes together.
  static constexpr std::size_t kMaxSearchSteps = 1'000'000;

  struct SearchResult {
    std::optional<OverloadChoice> best;  // a cheapest valid choice
    std::optional<OverloadChoice> tie;   // another one as cheap, if any
    std::size_t tieNode = 0;             // a node on which best and tie differ
    bool gaveUp = false;                 // stopped at kMaxSearchSteps
  };

  // Phase 3's fallback: every combination of the remaining candidates, producers before
  // consumers (order_), costing each node's overload and each edge exactly once; branch and
  // bound on the cost, which only grows as nodes are added.
  SearchResult exhaustiveSearch() const {
    SearchResult result;
    const std::size_t n = order_.size();
    std::vector<std::size_t> next(n, 0);
    std::vector<Cost> prefix(n + 1);
    OverloadChoice current(graph_.nodes.size());
    std::optional<Cost> best;
    std::size_t steps = 0;
    std::size_t position = 0;
    while (true) {
      if (position == n) {
        if (!best || prefix[n] < *best) {
          best = prefix[n];
          result.best = current;
          result.tie.reset();
        } else if (prefix[n] == *best && !result.tie) {
          result.tie = current;
        }
        if (n == 0)
          break;
        --position;
        continue;
      }
      const std::size_t node = order_[position];
      if (next[position] >= candidates_[node].size()) {
        next[position] = 0;
        current[node].reset();
        if (position == 0)
          break;
        --position;
        continue;
      }
      const std::size_t k = candidates_[node][next[position]++];
      if (++steps > kMaxSearchSteps) {
        result.gaveUp = true;
        result.best.reset();
        return result;
      }
      std::optional<Cost> cost = prefix[position] + ownCost(node, k);
      const auto& inputs = graph_.nodes[node].inputs;
      for (std::size_t s = 0; s < inputs.size() && cost; ++s) {
        if (!inputs[s] || inputs[s]->kind != InputSource::Kind::Link)
          continue;
        const std::size_t p = inputs[s]->producer;
        const auto edge = edgeCost(p, *current[p], inputs[s]->producerSocket, node, k, s);
        cost = edge ? std::optional(*cost + *edge) : std::nullopt;
      }
      if (!cost || (best && *cost > *best))
        continue;
      current[node] = k;
      prefix[position + 1] = *cost;
      ++position;
    }
    if (result.tie) {
      for (const std::size_t node : order_) {
        if ((*result.best)[node] != (*result.tie)[node]) {
          result.tieNode = node;
          break;
        }
      }
    }
    return result;
  }

  void reportAmbiguity(std::size_t node, const std::vector<std::size_t>& tied) {
    const auto& resolved = graph_.nodes[node];
    auto& d = diagnostics_.error(file_, resolved.source->location,
                                 "ambiguous: " + std::to_string(tied.size()) + " overloads of '" +
                                     nodeName(node) + "' fit this graph equally well");
    for (const auto k : tied) {
      d.notes.push_back("candidate: " + overloadSignature(*resolved.type, overload(node, k)));
    }
    for (std::size_t s = 0; s < resolved.inputs.size(); ++s) {
      const auto& input = resolved.inputs[s];
      if (!input || input->kind != InputSource::Kind::Link)
        continue;
      std::set<Type> arriving;
      for (const auto k : candidates_[input->producer]) {
        arriving.insert(socketType(input->producer, k, input->producerSocket));
      }
      d.notes.push_back("input '" + socketName(node, s) + "' arrives as " + joinTypes(arriving));
    }
    d.notes.push_back("make the choice explicit, e.g. convert the input first (Separate/Combine)");
  }

  const ResolvedGraph& graph_;
  const std::vector<std::size_t>& order_;
  const SourceFile& file_;
  Diagnostics& diagnostics_;
  std::vector<std::vector<std::size_t>> candidates_;
  std::vector<Edge> edges_;
  std::vector<char> varies_;  // per node: computeVarying()
};

}  // namespace

std::optional<OverloadChoice> inferTypes(const ResolvedGraph& graph,
                                         const std::vector<std::size_t>& order,
                                         const SourceFile& file, Diagnostics& diagnostics) {
  return Inference(graph, order, file, diagnostics).run();
}

}  // namespace memograph::compiler
