#include "graph_generator.h"

#include <cstdio>
#include <cstdlib>

#include "compiler/library_files.h"
#include "deterministic_random.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace memograph::testing {

namespace {

// The value a generated node produces. Each class maps to one plain shader type.
enum class ValueClass { Float, Float2, Float3, Color4 };
constexpr std::size_t kClassCount = 4;

// Graphs are identical on every standard library.
using Random = DeterministicRandom;

struct Input {
  std::string socket;
  std::size_t producer = 0;  // index of the producing node
};

struct PlannedNode {
  std::string type;
  std::vector<Input> inputs;
  std::vector<std::string> constants;  // "B=(2.00, 2.00)" or a positional "0.35"
  std::string output;                  // output socket; empty for sinks
  ValueClass value = ValueClass::Float3;
  // The node's output may be converted (splat, extended, truncated) at a consumer. True
  // only for nodes whose value width is fixed (sources, ImageTexture, Wave, Pick): for an
  // Add or Mul the conversion could as well happen before the node, at equal cost, and the
  // compiler reports such a graph as ambiguous. So arithmetic only feeds its own class.
  bool convertible = true;
  bool sink = false;
};

std::string number(Random& random, int lowHundredths, int highHundredths) {
  const int value =
      lowHundredths + static_cast<int>(random.below(highHundredths - lowHundredths + 1));
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value / 100.0);
  return text;
}

std::string tuple(Random& random, int components) {
  std::string text = "(";
  for (int i = 0; i < components; ++i)
    text += (i ? ", " : "") + number(random, 0, 100);
  return text + ")";
}

class Generator {
 public:
  explicit Generator(const GraphShape& shape) : shape_(shape), random_(shape.seed) {}

  std::string run() {
    const std::size_t target = std::max<std::size_t>(shape_.nodeCount, 1);
    if (shape_.textures && target >= 5)
      addTextureChain();
    while (nodes_.size() + finalCost(dangling_) < target) {
      const std::size_t budget = target - nodes_.size() - finalCost(dangling_);
      if (!addRandomNode(budget))
        break;
    }
    finish();
    return write();
  }

 private:
  using Dangling = std::array<std::vector<std::size_t>, kClassCount>;

  static std::size_t index(ValueClass value) { return static_cast<std::size_t>(value); }

  // Nodes that `finish` adds to connect every dangling output to a sink: an Add per merge,
  // a mixing node per float2/color output (and an ImageTexture before it for a float2 that
  // cannot be converted) and one sink per remaining root. `pending` is a node not added yet.
  std::size_t finalCost(const Dangling& dangling, const PlannedNode* pending = nullptr) const {
    const auto convertible = [&](std::size_t node) {
      return node < nodes_.size() ? nodes_[node].convertible : pending->convertible;
    };
    const std::size_t scalars = dangling[index(ValueClass::Float)].size();
    std::size_t vectors = dangling[index(ValueClass::Color4)].size();
    for (const std::size_t node : dangling[index(ValueClass::Float2)])
      vectors += convertible(node) ? 1 : 2;
    std::size_t colors = dangling[index(ValueClass::Float3)].size();
    if (colors == 0 && vectors > 0)
      colors = 1;  // the first mixing node starts a float3 chain
    return scalars + vectors + colors;
  }

  std::size_t add(PlannedNode node) {
    for (const auto& input : node.inputs)
      markConsumed(input.producer);
    nodes_.push_back(std::move(node));
    const std::size_t id = nodes_.size() - 1;
    if (!nodes_[id].sink) {
      dangling_[index(nodes_[id].value)].push_back(id);
      byClass_[index(nodes_[id].value)].push_back(id);
    }
    return id;
  }

  void markConsumed(std::size_t node) {
    auto& list = dangling_[index(nodes_[node].value)];
    const auto found = std::find(list.begin(), list.end(), node);
    if (found != list.end())
      list.erase(found);
  }

  // How many nodes `node` adds to the final count, itself included.
  std::size_t growth(const PlannedNode& node) const {
    Dangling after = dangling_;
    for (const auto& input : node.inputs) {
      auto& list = after[index(nodes_[input.producer].value)];
      const auto found = std::find(list.begin(), list.end(), input.producer);
      if (found != list.end())
        list.erase(found);
    }
    if (!node.sink)
      after[index(node.value)].push_back(nodes_.size());
    return 1 + finalCost(after, &node) - finalCost(dangling_);
  }

  // An existing node of a class: half the time one nothing reads yet (keeps the graph
  // connected), else a recent one (fan-out and reconvergence, and depth).
  std::optional<std::size_t> pick(ValueClass value, bool mustConvert = false) {
    const auto accept = [&](std::size_t node) { return !mustConvert || nodes_[node].convertible; };
    std::vector<std::size_t> open;
    for (const std::size_t node : dangling_[index(value)]) {
      if (accept(node))
        open.push_back(node);
    }
    if (!open.empty() && random_.chance(50))
      return open[random_.below(open.size())];
    const auto& all = byClass_[index(value)];
    constexpr std::size_t kWindow = 48;
    std::vector<std::size_t> recent;
    for (std::size_t i = all.size() > kWindow ? all.size() - kWindow : 0; i < all.size(); ++i) {
      if (accept(all[i]))
        recent.push_back(all[i]);
    }
    if (recent.empty())
      return std::nullopt;
    return recent[random_.below(recent.size())];
  }

  void addTextureChain() {
    const std::size_t uv = add({"UVInput", {}, {}, "UV", ValueClass::Float2});
    const std::size_t scaled =
        add({"Mul", {{"A", uv}}, {"B=" + tuple(random_, 2)}, "Out", ValueClass::Float2});
    add({"ImageTexture",
         {{"UV", scaled}},
         {"Image=\"textures/albedo.png\""},
         "Color",
         ValueClass::Color4});
  }

  std::optional<PlannedNode> source() {
    const std::size_t roll = random_.below(100);
    if (roll < 35) {
      PlannedNode node{"Float1Constant", {}, {}, "Out", ValueClass::Float};
      const std::string value = number(random_, 0, 100);
      node.constants.push_back(random_.chance(50) ? value : "Value=" + value);
      return node;
    }
    if (roll < 42)
      return PlannedNode{"TimeInput", {}, {}, "Out", ValueClass::Float};
    if (roll < 55 && shape_.textures)
      return PlannedNode{"UVInput", {}, {}, "UV", ValueClass::Float2};
    if (roll < 68)
      return PlannedNode{"NormalInput", {}, {}, "Out", ValueClass::Float3};
    if (roll < 78)
      return PlannedNode{"PositionInput", {}, {}, "Out", ValueClass::Float3};
    PlannedNode node{"Float3Constant", {}, {}, "Out", ValueClass::Float3};
    if (random_.chance(30)) {
      node.constants = {number(random_, 0, 100), number(random_, 0, 100), number(random_, 0, 100)};
    } else {
      node.constants.push_back((random_.chance(50) ? "" : "Value=") + tuple(random_, 3));
    }
    return node;
  }

  ValueClass arithmeticClass() {
    const std::size_t roll = random_.below(100);
    if (roll < 55)
      return ValueClass::Float3;
    if (roll < 85 || !shape_.textures)
      return ValueClass::Float;
    return ValueClass::Float2;
  }

  // Add or Mul of two links of one class.
  std::optional<PlannedNode> binary() {
    const ValueClass value = arithmeticClass();
    const auto a = pick(value);
    const auto b = pick(value);
    if (!a || !b)
      return std::nullopt;
    PlannedNode node{random_.chance(50) ? "Add" : "Mul", {{"A", *a}, {"B", *b}}, {}, "Out", value};
    node.convertible = false;
    return node;
  }

  // Add or Mul of a link and a constant (or the socket's default).
  std::optional<PlannedNode> unary() {
    const ValueClass value = arithmeticClass();
    const auto a = pick(value);
    if (!a)
      return std::nullopt;
    PlannedNode node{random_.chance(50) ? "Add" : "Mul", {{"A", *a}}, {}, "Out", value};
    node.convertible = false;
    if (value == ValueClass::Float2) {
      // A full-width tuple: a splatting scalar would let the node be any vector width, and
      // the ImageTexture it feeds only says float2 after a truncation.
      node.constants.push_back("B=" + tuple(random_, 2));
      return node;
    }
    const std::size_t roll = random_.below(100);
    if (roll < 20)
      return node;  // B takes its @default
    if (value == ValueClass::Float3 && roll < 50) {
      node.constants.push_back("B=" + tuple(random_, 3));
    } else if (roll < 75) {
      node.constants.push_back("B=" + number(random_, 10, 300));
    } else {
      node.constants.push_back(number(random_, 10, 300));  // positional: fills B
    }
    return node;
  }

  // A float, float2 or texture color brought into the float3 part of the graph.
  std::optional<PlannedNode> mixing() {
    const std::size_t roll = random_.below(100);
    const ValueClass from = roll < 40   ? ValueClass::Float
                            : roll < 70 ? ValueClass::Color4
                                        : ValueClass::Float2;
    const auto a = pick(from, true);
    if (!a)
      return std::nullopt;
    return pickOf(*a);
  }

  // Pick between a value `a` of fixed width and a float3 (`b`, any when not given, or `a`
  // itself when there is none): Pick's single float3 overload fixes where `a` is splat,
  // extended or truncated. Through Add or Mul the conversion could as well happen on
  // either side of the node, at equal cost, and the compiler reports that as ambiguous.
  PlannedNode pickOf(std::size_t a, std::optional<std::size_t> b = std::nullopt) {
    if (!b)
      b = pick(ValueClass::Float3);
    PlannedNode node{"Pick", {{"A", a}, {"B", b.value_or(a)}}, {}, "Out", ValueClass::Float3};
    if (random_.chance(50))
      std::swap(node.inputs[0].producer, node.inputs[1].producer);
    const std::string mode = std::to_string(random_.below(2));
    node.constants.push_back(random_.chance(50) ? mode : "Mode=" + mode);  // positional: Mode
    return node;
  }

  std::optional<PlannedNode> texture() {
    if (!shape_.textures)
      return std::nullopt;
    const auto uv = pick(ValueClass::Float2);
    if (!uv)
      return std::nullopt;
    PlannedNode node{"ImageTexture", {{"UV", *uv}}, {}, "Color", ValueClass::Color4};
    const std::string path = "\"textures/t" + std::to_string(random_.below(8)) + ".png\"";
    node.constants.push_back(random_.chance(50) ? path : "Image=" + path);
    return node;
  }

  std::optional<PlannedNode> wave() {
    const auto in = pick(ValueClass::Float3);
    if (!in)
      return std::nullopt;
    return PlannedNode{"Wave", {{"In", *in}}, {}, "Out", ValueClass::Float};
  }

  std::optional<PlannedNode> pickNode() {
    const auto a = pick(ValueClass::Float3);
    const auto b = pick(ValueClass::Float3);
    if (!a || !b)
      return std::nullopt;
    PlannedNode node{"Pick", {{"A", *a}, {"B", *b}}, {}, "Out", ValueClass::Float3};
    const std::string mode = std::to_string(random_.below(2));
    node.constants.push_back(random_.chance(50) ? mode : "Mode=" + mode);
    return node;
  }

  std::optional<PlannedNode> randomNode() {
    const std::size_t roll = random_.below(100);
    if (roll < 18)
      return source();
    if (roll < 48)
      return binary();
    if (roll < 68)
      return unary();
    if (roll < 80)
      return mixing();
    if (roll < 88)
      return texture();
    if (roll < 94)
      return wave();
    return pickNode();
  }

  // Adds a node that fits within `budget` more nodes; false when none can.
  bool addRandomNode(std::size_t budget) {
    for (int attempt = 0; attempt < 32; ++attempt) {
      auto node = randomNode();
      if (node && growth(*node) <= budget) {
        add(std::move(*node));
        return true;
      }
    }
    // Deterministic fallbacks: a constant source, or a node that consumes a dangling output
    // and produces one of the same class (grows the count by exactly one).
    if (nodes_.empty()) {
      if (budget < 2)
        return false;
      add({"Float1Constant", {}, {"0.50"}, "Out", ValueClass::Float});
      return true;
    }
    for (const ValueClass value : {ValueClass::Float3, ValueClass::Float}) {
      if (dangling_[index(value)].empty())
        continue;
      add({"Add", {{"A", dangling_[index(value)].front()}}, {}, "Out", value, false});
      return true;
    }
    if (!dangling_[index(ValueClass::Color4)].empty()) {
      add(pickOf(dangling_[index(ValueClass::Color4)].front()));
      return true;
    }
    const std::size_t uv = dangling_[index(ValueClass::Float2)].front();
    if (nodes_[uv].convertible) {
      add(pickOf(uv));
    } else {
      add({"ImageTexture", {{"UV", uv}}, {"\"textures/detail.png\""}, "Color", ValueClass::Color4});
    }
    return true;
  }

  // Merges `roots` pairwise with Add until `keep` remain.
  std::vector<std::size_t> merge(std::vector<std::size_t> roots, ValueClass value,
                                 std::size_t keep) {
    while (roots.size() > keep) {
      random_.shuffle(roots);
      const std::size_t a = roots.back();
      roots.pop_back();
      const std::size_t b = roots.back();
      roots.pop_back();
      PlannedNode node{"Add", {{"A", a}, {"B", b}}, {}, "Out", value};
      roots.insert(roots.begin(), add(std::move(node)));
    }
    return roots;
  }

  // Connects every output nothing reads to a sink.
  void finish() {
    std::vector<std::size_t> vectors;
    const auto uvs = dangling_[index(ValueClass::Float2)];  // a copy: add() edits the list
    for (std::size_t a : uvs) {
      if (!nodes_[a].convertible) {
        const std::string path = "\"textures/detail.png\"";
        a = add({"ImageTexture", {{"UV", a}}, {path}, "Color", ValueClass::Color4});
      }
      vectors.push_back(a);
    }
    const auto colors = dangling_[index(ValueClass::Color4)];
    vectors.insert(vectors.end(), colors.begin(), colors.end());
    std::sort(vectors.begin(), vectors.end());
    vectors.erase(std::unique(vectors.begin(), vectors.end()), vectors.end());
    for (const std::size_t a : vectors) {
      const auto& open = dangling_[index(ValueClass::Float3)];
      std::optional<std::size_t> b;
      if (!open.empty())
        b = open[random_.below(open.size())];
      add(pickOf(a, b));
    }
    const auto scalars = merge(dangling_[index(ValueClass::Float)], ValueClass::Float, 1);
    for (const std::size_t root : scalars)
      add({"RoughnessOutput", {{"Roughness", root}}, {}, "", ValueClass::Float, true, true});
    const auto roots = merge(dangling_[index(ValueClass::Float3)], ValueClass::Float3, 2);
    if (roots.size() == 2) {
      add({"BaseColorOutput", {{"Color", roots[0]}}, {}, "", ValueClass::Float3, true, true});
      add({"EmissionOutput", {{"Color", roots[1]}}, {}, "", ValueClass::Float3, true, true});
    } else if (roots.size() == 1) {
      const char* sink = random_.chance(50) ? "ColorOutput" : "BaseColorOutput";
      const char* socket = sink[0] == 'C' ? "In" : "Color";
      add({sink, {{socket, roots[0]}}, {}, "", ValueClass::Float3, true, true});
    }
    if (nodes_.empty())
      add({"RoughnessOutput", {}, {"Roughness=0.50"}, "", ValueClass::Float, true, true});
  }

  std::string write() {
    // Link ids are a shuffled numbering of the nodes that produce something.
    std::vector<std::size_t> linkOf(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      linkOf[i] = i;
    random_.shuffle(linkOf);
    std::vector<std::string> statements;
    statements.reserve(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      const PlannedNode& node = nodes_[i];
      std::vector<std::string> items;
      for (const auto& input : node.inputs)
        items.push_back(input.socket + "<" + std::to_string(linkOf[input.producer]));
      for (const auto& constant : node.constants)
        items.push_back(constant);
      if (!node.output.empty())
        items.push_back(node.output + ">" + std::to_string(linkOf[i]));
      std::string statement = node.type;
      for (const auto& item : items)
        statement += " " + item;
      statements.push_back(statement + ";");
    }
    random_.shuffle(statements);
    std::string text =
        "# Generated by memograph::testing::generateGraph: " + std::to_string(nodes_.size()) +
        " nodes, seed " + std::to_string(shape_.seed) + ".\n";
    if (!shape_.materialName.empty())
      text += "material " + shape_.materialName + ";\n";
    for (const auto& statement : statements)
      text += statement + "\n";
    return text;
  }

  GraphShape shape_;
  Random random_;
  std::vector<PlannedNode> nodes_;
  Dangling dangling_;
  Dangling byClass_;  // every non-sink node, per class, in creation order
};

}  // namespace

std::string generateGraph(const GraphShape& shape) {
  return Generator(shape).run();
}

std::vector<compiler::SourceFile> generateGraphSet(std::size_t count, std::size_t nodeCount,
                                                   std::uint64_t firstSeed) {
  std::vector<compiler::SourceFile> graphs;
  graphs.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    GraphShape shape;
    shape.nodeCount = nodeCount;
    shape.seed = firstSeed + i;
    graphs.push_back({"generated_" + std::to_string(shape.seed) + ".mgraph", generateGraph(shape)});
  }
  return graphs;
}

std::string testNodeLibraryDirectory() {
  return MEMOGRAPH_TEST_NODES_DIR;
}

const compiler::NodeLibrary& testNodeLibrary() {
  static const compiler::NodeLibrary library = [] {
    compiler::Diagnostics diagnostics;
    const auto files = compiler::readNodeLibraryDirectory(testNodeLibraryDirectory(), diagnostics);
    auto loaded = compiler::NodeLibrary::load(files.value_or(std::vector<compiler::SourceFile>{}),
                                              diagnostics);
    if (diagnostics.hasErrors()) {
      std::fputs(compiler::formatDiagnostics(diagnostics).c_str(), stderr);
      std::abort();
    }
    return loaded;
  }();
  return library;
}

}  // namespace memograph::testing
