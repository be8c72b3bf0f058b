#include "compiler/node_library.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <unordered_map>

#include "compiler/library_scanner.h"
#include "compiler/literal.h"
#include "compiler/material_interface.h"

namespace memograph::compiler {

namespace {

// Words reserved in GLSL or HLSL that a careless socket name might hit.
const std::set<std::string, std::less<>> kReservedNames = {
    "input",
    "output",
    "sample",
    "texture",
    "filter",
    "packed",
    "line",
    "point",
    "linear",
    "common",
    "partition",
    "active",
    "buffer",
    "shared",
    "in",
    "out",
    "inout",
    "uniform",
    "precision",
    "centroid",
    "smooth",
    "flat",
    "patch",
    "half",
    "double",
    "matrix",
    "vector",
    "string",
    "register",
    "groupshared",
    "nointerpolation",
    "triangle",
    "lineadj",
    "triangleadj",
    "export",
    "extern",
    "static",
    "volatile",
    "namespace",
    "cast",
    "template",
    "this",
    "typedef",
    "union",
    "unsigned",
    "using",
};

struct RawParameter {
  Direction direction = Direction::In;
  std::string type;
  std::string name;
};

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos)
    return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return std::string(text.substr(first, last - first + 1));
}

std::vector<std::string> splitWords(std::string_view text) {
  std::vector<std::string> words;
  std::istringstream stream{std::string(text)};
  for (std::string word; stream >> word;)
    words.push_back(word);
  return words;
}

// "in float3 A, out float3 Out" → parameters. Empty on a malformed list.
std::optional<std::vector<RawParameter>> parseParameters(std::string_view list) {
  std::vector<RawParameter> parameters;
  if (trim(list).empty() || trim(list) == "void")
    return parameters;
  std::size_t start = 0;
  while (start <= list.size()) {
    auto comma = list.find(',', start);
    if (comma == std::string_view::npos)
      comma = list.size();
    auto words = splitWords(list.substr(start, comma - start));
    RawParameter parameter;
    if (!words.empty() && (words[0] == "in" || words[0] == "out" || words[0] == "inout")) {
      parameter.direction = words[0] == "in"    ? Direction::In
                            : words[0] == "out" ? Direction::Out
                                                : Direction::InOut;
      words.erase(words.begin());
    }
    if (words.size() != 2)
      return std::nullopt;
    parameter.type = words[0];
    parameter.name = words[1];
    parameters.push_back(parameter);
    start = comma + 1;
  }
  return parameters;
}

struct Annotations {
  std::string description;
  std::vector<std::pair<std::string, std::vector<std::string>>> typeVariables;
  std::vector<std::pair<std::string, std::string>> defaults;  // socket, value text
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
};

bool isKnownInput(std::string_view name) {
  return std::find(kMaterialInputNames.begin(), kMaterialInputNames.end(), name) !=
         kMaterialInputNames.end();
}

bool isKnownOutput(std::string_view name) {
  return std::find(kMaterialOutputNames.begin(), kMaterialOutputNames.end(), name) !=
         kMaterialOutputNames.end();
}

// Bounds on @types (docs/guide/limits.md).
constexpr std::size_t kMaxTypeInstances = 64;
constexpr std::size_t kMaxTypeVariables = 16;

class Loader {
 public:
  Loader(NodeLibrary::Parts& parts, Diagnostics& diagnostics)
      : parts_(parts), diagnostics_(diagnostics) {}

  void loadFile(const SourceFile& file) {
    const bool isPrelude = file.path.starts_with("prelude/");
    const bool glslOnly = file.path == "prelude/glsl.inc";
    const bool hlslOnly = file.path == "prelude/hlsl.inc";
    std::optional<Target> onlyTarget;
    if (glslOnly)
      onlyTarget = Target::Glsl;
    if (hlslOnly)
      onlyTarget = Target::Hlsl;
    for (const auto& item : scanLibraryFile(file, diagnostics_)) {
      if (isPrelude) {
        addToPrelude(file, item, onlyTarget);
        continue;
      }
      if (item.kind != LibraryItem::Kind::Function || item.isPrototype) {
        diagnostics_.error(file, item.location,
                           "node files hold only function definitions; structs, prototypes and "
                           "preprocessor lines belong in the prelude");
        continue;
      }
      addFunction(file, item);
    }
  }

  void finish() {
    linkCallees();
    markInventedDerivatives();
    std::sort(parts_.nodeTypes.begin(), parts_.nodeTypes.end(),
              [](const NodeType& a, const NodeType& b) { return a.name < b.name; });
  }

 private:
  std::optional<Annotations> parseAnnotations(const SourceFile& file, const LibraryItem& item) {
    Annotations annotations;
    for (const auto& line : item.docLines) {
      if (!line.starts_with("@")) {
        if (!line.empty()) {
          annotations.description += (annotations.description.empty() ? "" : " ") + line;
        }
        continue;
      }
      const auto words = splitWords(line);
      const std::string& tag = words[0];
      if (tag == "@types") {
        // @types T = a, b; S = c, d
        std::string rest = line.substr(6);
        std::stringstream groups(rest);
        for (std::string group; std::getline(groups, group, ';');) {
          const auto equals = group.find('=');
          if (equals == std::string::npos) {
            diagnostics_.error(file, item.location, "malformed @types: expected `T = a, b, …`");
            return std::nullopt;
          }
          std::vector<std::string> types;
          std::stringstream list(group.substr(equals + 1));
          for (std::string type; std::getline(list, type, ',');)
            types.push_back(trim(type));
          annotations.typeVariables.emplace_back(trim(group.substr(0, equals)), types);
        }
      } else if (tag == "@default" && words.size() >= 3) {
        const auto valueStart = line.find(words[1]) + words[1].size();
        annotations.defaults.emplace_back(words[1], trim(line.substr(valueStart)));
      } else if (tag == "@input" && words.size() == 2 && isKnownInput(words[1])) {
        annotations.inputs.push_back(words[1]);
      } else if (tag == "@output" && words.size() == 2 && isKnownOutput(words[1])) {
        annotations.outputs.push_back(words[1]);
      } else {
        diagnostics_.error(file, item.location, "unknown or malformed annotation '" + line + "'");
        return std::nullopt;
      }
    }
    const std::size_t count =
        annotations.typeVariables.empty() ? 0 : annotations.typeVariables[0].second.size();
    // Each instance is a function of its own: a bound keeps a tiny file from costing
    // gigabytes (docs/guide/limits.md; the library's longest list has 8 types).
    if (count > kMaxTypeInstances || annotations.typeVariables.size() > kMaxTypeVariables) {
      diagnostics_.error(file, item.location,
                         "@types lists " + std::to_string(count) + " types for " +
                             std::to_string(annotations.typeVariables.size()) +
                             " variables; the limits are " + std::to_string(kMaxTypeInstances) +
                             " types and " + std::to_string(kMaxTypeVariables) +
                             " variables (docs/guide/limits.md)");
      return std::nullopt;
    }
    for (const auto& [variable, types] : annotations.typeVariables) {
      if (types.size() != count || variable.empty()) {
        diagnostics_.error(file, item.location,
                           "every @types list must have the same number of types");
        return std::nullopt;
      }
    }
    return annotations;
  }

  // The item once per @types instance, type variables substituted.
  static std::vector<LibraryItem> instantiate(const LibraryItem& item,
                                              const Annotations& annotations) {
    if (annotations.typeVariables.empty())
      return {item};
    std::vector<LibraryItem> instances;
    const std::size_t count = annotations.typeVariables[0].second.size();
    // The doc lines (which hold the @types list itself) are not copied into each instance:
    // with them, n types cost n copies of an n-long list, memory quadratic in n.
    LibraryItem base = item;
    base.docLines.clear();
    instances.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      LibraryItem instance = base;
      for (const auto& [variable, types] : annotations.typeVariables) {
        instance.name = replaceWord(instance.name, variable, types[i]);  // mg_make_T_D
        instance.text = replaceWord(instance.text, variable, types[i]);
        instance.returnType = replaceWord(instance.returnType, variable, types[i]);
        instance.parameterList = replaceWord(instance.parameterList, variable, types[i]);
      }
      instances.push_back(std::move(instance));
    }
    return instances;
  }

  static std::string guardFor(const std::string& name, const std::vector<RawParameter>& params) {
    std::string guard = "MG_FN_" + name;
    for (const auto& p : params)
      guard += "_" + p.type;
    return guard;
  }

  // One template instance as a library function (prelude helper, family helper or node).
  static LibraryFunction functionOf(const SourceFile& file, const LibraryItem& item,
                                    const LibraryItem& instance,
                                    const std::vector<RawParameter>& parameters) {
    LibraryFunction function;
    function.name = instance.name;
    function.returnType = instance.returnType;
    function.text = instance.text;
    function.guard = guardFor(instance.name, parameters);
    for (const RawParameter& parameter : parameters)
      function.parameterTypes.push_back(parameter.type);
    function.file = file.path;
    function.location = item.location;
    return function;
  }

  void reportUnreadableParameters(const SourceFile& file, const LibraryItem& item) {
    diagnostics_.error(file, item.location,
                       "cannot read the parameters of '" + item.name +
                           "': write `[in|out|inout] Type name` separated by commas");
  }

  // Preprocessor lines, structs and prototypes go to every include; functions become
  // LibraryFunctions like the families' helpers, emitted only when reached.
  void addToPrelude(const SourceFile& file, const LibraryItem& item,
                    std::optional<Target> onlyTarget) {
    std::string text;
    if (item.kind == LibraryItem::Kind::Function && !item.isPrototype) {
      const auto annotations = parseAnnotations(file, item);
      if (!annotations)
        return;
      for (const auto& instance : instantiate(item, *annotations)) {
        const auto parameters = parseParameters(instance.parameterList);
        if (!parameters)
          return reportUnreadableParameters(file, item);
        LibraryFunction function = functionOf(file, item, instance, *parameters);
        function.prelude = true;
        function.onlyTarget = onlyTarget;
        text += "#ifndef " + function.guard + "\n#define " + function.guard + "\n" + function.text +
                "\n#endif\n";
        parts_.functionsByName[function.name].push_back(parts_.functions.size());
        recordSignature(*parameters, function.returnType);
        parts_.functions.push_back(std::move(function));
      }
      append(text, onlyTarget, false);
      return;
    }
    append(item.text + "\n", onlyTarget, true);
  }

  void append(const std::string& text, std::optional<Target> onlyTarget, bool declaration) {
    if (onlyTarget != Target::Hlsl) {
      parts_.glslPrelude += text;
      if (declaration)
        parts_.glslDeclarations += text;
    }
    if (onlyTarget != Target::Glsl) {
      parts_.hlslPrelude += text;
      if (declaration)
        parts_.hlslDeclarations += text;
    }
  }

  void addFunction(const SourceFile& file, const LibraryItem& item) {
    const auto annotations = parseAnnotations(file, item);
    if (!annotations)
      return;
    const bool isNode =
        item.returnType == "void" && std::isupper(static_cast<unsigned char>(item.name[0]));
    for (const auto& instance : instantiate(item, *annotations)) {
      const auto parameters = parseParameters(instance.parameterList);
      if (!parameters)
        return reportUnreadableParameters(file, item);
      LibraryFunction function = functionOf(file, item, instance, *parameters);
      if (isNode && !addNodeOverload(file, item, *annotations, *parameters, function))
        return;
      if (!isNode && !item.name.starts_with("mg_")) {
        diagnostics_.error(file, item.location,
                           "'" + item.name +
                               "' is neither a node (a void function named in PascalCase) nor "
                               "a helper (a function named mg_…)");
        return;
      }
      parts_.functionsByName[function.name].push_back(parts_.functions.size());
      recordSignature(*parameters, function.returnType);
      parts_.functions.push_back(std::move(function));
    }
  }

  bool addNodeOverload(const SourceFile& file, const LibraryItem& item,
                       const Annotations& annotations, const std::vector<RawParameter>& raw,
                       LibraryFunction& function) {
    Overload overload;
    overload.function = parts_.functions.size();
    std::vector<Socket> sockets;
    bool takesInputs = false;
    bool isSink = false;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      const auto type = Type::parse(raw[i].type);
      if (!type) {
        diagnostics_.error(file, item.location,
                           "node '" + item.name + "' has parameter '" + raw[i].name +
                               "' of type '" + raw[i].type +
                               "'; sockets are float, float2/3/4 (optionally _D), int, "
                               "TextureRef or Table");
        return false;
      }
      function.parameters.push_back(Parameter{raw[i].direction, *type, raw[i].name});
      if (type->base == BaseType::Inputs) {
        takesInputs = true;
        continue;
      }
      if (type->base == BaseType::Outputs) {
        if (raw[i].direction != Direction::InOut) {
          diagnostics_.error(file, item.location,
                             "MaterialOutputs must be passed as `inout MaterialOutputs outputs`");
          return false;
        }
        isSink = true;
        continue;
      }
      if (raw[i].direction == Direction::InOut) {
        diagnostics_.error(file, item.location,
                           "socket '" + raw[i].name + "' of '" + item.name +
                               "' is inout; sockets are `in` (inputs) or `out` (outputs)");
        return false;
      }
      // Tables and texture slots come only from literals: no node can produce one.
      if (raw[i].direction == Direction::Out &&
          (type->base == BaseType::Table || type->base == BaseType::TextureRef)) {
        diagnostics_.error(file, item.location,
                           "output '" + raw[i].name + "' of '" + item.name + "' is a " +
                               type->name() + "; tables and textures can only be inputs");
        return false;
      }
      if (kReservedNames.contains(raw[i].name)) {
        diagnostics_.error(
            file, item.location,
            "socket name '" + raw[i].name + "' is reserved in GLSL or HLSL; choose another");
        return false;
      }
      sockets.push_back(Socket{raw[i].name, raw[i].direction, i});
      overload.socketTypes.push_back(*type);
      if (type->derivatives) {
        ++(raw[i].direction == Direction::In ? overload.derivativeInputs
                                             : overload.derivativeOutputs);
      }
    }
    auto found = nodeIndex_.find(item.name);
    if (found == nodeIndex_.end()) {
      NodeType node;
      node.name = item.name;
      node.description = annotations.description;
      node.sockets = sockets;
      node.isSink = isSink;
      node.takesInputs = takesInputs;
      node.file = file.path;
      node.location = item.location;
      found = nodeIndex_.emplace(item.name, parts_.nodeTypes.size()).first;
      parts_.nodeTypes.push_back(std::move(node));
    }
    NodeType& node = parts_.nodeTypes[found->second];
    const bool sameSockets = node.sockets.size() == sockets.size() &&
                             std::equal(sockets.begin(), sockets.end(), node.sockets.begin(),
                                        [](const Socket& a, const Socket& b) {
                                          return a.name == b.name && a.direction == b.direction;
                                        });
    if (!sameSockets || node.isSink != isSink) {
      diagnostics_.error(file, item.location,
                         "this overload of '" + item.name +
                             "' has different sockets from the one at " + node.file + ":" +
                             std::to_string(node.location.line) +
                             "; all overloads of a node share socket names and directions");
      return false;
    }
    // Overloads differ in parameters, so sockets read the same inputs; keep what any says.
    node.takesInputs = node.takesInputs || takesInputs;
    if (node.description.empty())
      node.description = annotations.description;
    for (const auto& [socket, valueText] : annotations.defaults) {
      if (node.socketIndex(socket) < 0) {
        diagnostics_.error(
            file, item.location,
            "@default names '" + socket + "', which is not a socket of '" + item.name + "'");
        return false;
      }
      const auto value = parseLiteral(valueText);
      if (!value) {
        diagnostics_.error(
            file, item.location,
            "@default " + socket + ": '" + valueText + "' is not a number or a (x, y, …) tuple");
        return false;
      }
      node.defaults[socket] = *value;
    }
    for (const auto& input : annotations.inputs) {
      if (std::find(node.inputsRead.begin(), node.inputsRead.end(), input) ==
          node.inputsRead.end()) {
        node.inputsRead.push_back(input);
      }
    }
    for (const auto& output : annotations.outputs) {
      if (std::find(node.outputsWritten.begin(), node.outputsWritten.end(), output) ==
          node.outputsWritten.end()) {
        node.outputsWritten.push_back(output);
      }
    }
    for (const auto& existing : node.overloads) {
      if (existing.socketTypes == overload.socketTypes) {
        diagnostics_.error(file, item.location,
                           "'" + item.name + "' is defined twice with the same socket types");
        return false;
      }
    }
    node.overloads.push_back(std::move(overload));
    return true;
  }

  // A `_D` type or a name built on one: float3_D, mg_make_float3_D, mg_const_D.
  static bool namesDerivatives(std::string_view identifier) {
    return identifier.ends_with("_D") || identifier.find("_D_") != std::string_view::npos;
  }

  void recordSignature(const std::vector<RawParameter>& parameters, const std::string& returnType) {
    derivativeParameters_.push_back(
        std::any_of(parameters.begin(), parameters.end(),
                    [](const RawParameter& p) { return namesDerivatives(p.type); }));
    // Makes a `_D` value from plain ones (mg_make_float3_D, mg_const_D).
    returnsDerivatives_.push_back(namesDerivatives(returnType) && !derivativeParameters_.back());
  }

  // Whether a function body can hold a `_D` value: it names a `_D` type or function, reads
  // MaterialInputs (uv, position, … are `_D`), or calls a name one of whose overloads makes
  // a `_D` value from plain ones. Only then can it call an overload with a `_D` parameter.
  bool mayHoldDerivatives(const std::vector<std::string_view>& identifiers) const {
    for (const auto identifier : identifiers) {
      if (namesDerivatives(identifier) || identifier == "inputs" ||
          identifier == "MaterialInputs") {
        return true;
      }
      const auto found = parts_.functionsByName.find(identifier);
      if (found != parts_.functionsByName.end() &&
          std::any_of(found->second.begin(), found->second.end(),
                      [&](std::size_t f) { return returnsDerivatives_[f]; })) {
        return true;
      }
    }
    return false;
  }

  void linkCallees() {
    for (std::size_t i = 0; i < parts_.functions.size(); ++i) {
      auto& function = parts_.functions[i];
      std::set<std::size_t> callees;
      bool definitionSeen = false;
      const auto identifiers = identifiersIn(function.text);
      // A body without `_D` values cannot call the overloads that take one: leaving them
      // out keeps a plain material from carrying the whole derivative arithmetic.
      const bool derivatives = mayHoldDerivatives(identifiers);
      for (const auto identifier : identifiers) {
        const auto found = parts_.functionsByName.find(identifier);
        if (found == parts_.functionsByName.end())
          continue;
        const bool ownName = identifier == function.name;
        // The first occurrence of its own name is its definition, not a call.
        if (ownName && !definitionSeen) {
          definitionSeen = true;
          continue;
        }
        // A call of its own name: the overloads defined before it (GLSL and HLSL call only
        // what is declared above).
        for (const std::size_t callee : found->second) {
          if ((!ownName || callee < i) && (derivatives || !derivativeParameters_[callee]))
            callees.insert(callee);
        }
      }
      function.callees.assign(callees.begin(), callees.end());
    }
  }

  // Overload::inventsDerivatives, from the MaterialInputs members the node reads (@input).
  void markInventedDerivatives() {
    auto isAny = [](const std::string& member, std::initializer_list<std::string_view> names) {
      return std::find(names.begin(), names.end(), member) != names.end();
    };
    for (auto& node : parts_.nodeTypes) {
      const bool readsDerivatives = std::any_of(
          node.inputsRead.begin(), node.inputsRead.end(), [&](const std::string& member) {
            return isAny(member, {"uv", "position", "generated", "objectPosition"});
          });
      const bool readsVaryingPlain = std::any_of(
          node.inputsRead.begin(), node.inputsRead.end(), [&](const std::string& member) {
            return isAny(member, {"normal", "tangent", "vertexColor", "view", "geometricNormal"});
          });
      const bool hasInputSockets =
          std::any_of(node.sockets.begin(), node.sockets.end(),
                      [](const Socket& socket) { return socket.direction == Direction::In; });
      for (auto& overload : node.overloads) {
        overload.inventsDerivatives = node.takesInputs && !hasInputSockets &&
                                      overload.derivativeOutputs > 0 && !readsDerivatives &&
                                      readsVaryingPlain;
      }
    }
  }

  NodeLibrary::Parts& parts_;
  Diagnostics& diagnostics_;
  std::unordered_map<std::string, std::size_t> nodeIndex_;
  std::vector<char> derivativeParameters_;  // per function: a parameter of a `_D` type
  std::vector<char> returnsDerivatives_;    // per function: a `_D` result from plain ones
};

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      current[j] =
          std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (same ? 0 : 1)});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

}  // namespace

int NodeType::socketIndex(std::string_view socketName) const {
  for (std::size_t i = 0; i < sockets.size(); ++i) {
    if (sockets[i].name == socketName)
      return static_cast<int>(i);
  }
  return -1;
}

NodeLibrary NodeLibrary::load(const std::vector<SourceFile>& files, Diagnostics& diagnostics) {
  NodeLibrary library;
  Loader loader(library.parts_, diagnostics);
  // Target-specific prelude first, then the portable one, then the families: sort so the
  // order never depends on how the caller listed the files.
  std::vector<const SourceFile*> ordered;
  for (const auto& file : files)
    ordered.push_back(&file);
  auto rank = [](const SourceFile* file) {
    if (file->path == "prelude/glsl.inc" || file->path == "prelude/hlsl.inc")
      return 0;
    if (file->path.starts_with("prelude/"))
      return 1;
    return 2;
  };
  std::sort(ordered.begin(), ordered.end(), [&](const SourceFile* a, const SourceFile* b) {
    return std::pair(rank(a), a->path) < std::pair(rank(b), b->path);
  });
  for (const auto* file : ordered)
    loader.loadFile(*file);
  loader.finish();
  return library;
}

const std::vector<std::size_t>& NodeLibrary::functionsNamed(std::string_view name) const {
  static const std::vector<std::size_t> kNone;
  const auto found = parts_.functionsByName.find(name);
  return found == parts_.functionsByName.end() ? kNone : found->second;
}

std::optional<std::size_t> NodeLibrary::specialisation(const NodeType& node, std::size_t overload,
                                                       std::size_t socket, long long value) const {
  const LibraryFunction& general = parts_.functions[node.overloads.at(overload).function];
  std::vector<std::string> wanted = general.parameterTypes;
  const std::size_t removed = node.sockets.at(socket).parameterIndex;
  if (removed >= wanted.size())
    return std::nullopt;
  wanted.erase(wanted.begin() + static_cast<std::ptrdiff_t>(removed));
  const std::string name =
      "mg_spec_" + node.name + "_" + node.sockets[socket].name + "_" + std::to_string(value);
  for (const std::size_t candidate : functionsNamed(name)) {
    if (parts_.functions[candidate].parameterTypes == wanted)
      return candidate;
  }
  return std::nullopt;
}

const NodeType* NodeLibrary::find(std::string_view name) const {
  const auto found =
      std::lower_bound(parts_.nodeTypes.begin(), parts_.nodeTypes.end(), name,
                       [](const NodeType& node, std::string_view key) { return node.name < key; });
  return found != parts_.nodeTypes.end() && found->name == name ? &*found : nullptr;
}

std::vector<std::string> NodeLibrary::suggestions(std::string_view name) const {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::size_t limit = std::max<std::size_t>(2, name.size() / 3);
  for (const auto& node : parts_.nodeTypes) {
    // The distance is at least the difference in length; skipping on it keeps a huge
    // unknown name (megabytes from a fuzzer) from costing its length times every name.
    const std::size_t lengthDifference = name.size() > node.name.size()
                                             ? name.size() - node.name.size()
                                             : node.name.size() - name.size();
    if (lengthDifference > limit)
      continue;
    const auto distance = editDistance(name, node.name);
    if (distance <= limit)
      scored.emplace_back(distance, node.name);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> result;
  for (std::size_t i = 0; i < scored.size() && i < 3; ++i)
    result.push_back(scored[i].second);
  return result;
}

}  // namespace memograph::compiler
