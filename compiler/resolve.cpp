#include "compiler/resolved_graph.h"

#include <algorithm>
#include <map>
#include <set>

#include "compiler/literal.h"

namespace memograph::compiler {

namespace {

std::string socketList(const NodeType& type, Direction direction) {
  std::string list;
  for (const auto& socket : type.sockets) {
    if (socket.direction != direction)
      continue;
    list += (list.empty() ? "" : ", ") + socket.name;
  }
  return list.empty() ? "none" : list;
}

// Whether every overload of the socket takes a TextureRef (strings bind only there).
bool isTextureSocket(const NodeType& type, std::size_t socket) {
  for (const auto& overload : type.overloads) {
    if (overload.socketTypes[socket].base != BaseType::TextureRef)
      return false;
  }
  return !type.overloads.empty();
}

// Whether every overload of the socket takes a Table (bracket literals bind only there).
bool isTableSocket(const NodeType& type, std::size_t socket) {
  for (const auto& overload : type.overloads) {
    if (overload.socketTypes[socket].base != BaseType::Table)
      return false;
  }
  return !type.overloads.empty();
}

bool isIntSocket(const NodeType& type, std::size_t socket) {
  for (const auto& overload : type.overloads) {
    if (overload.socketTypes[socket].base != BaseType::Int)
      return false;
  }
  return !type.overloads.empty();
}

class Resolver {
 public:
  Resolver(const Graph& graph, const SourceFile& file, const NodeLibrary& library,
           Diagnostics& diagnostics)
      : graph_(graph), file_(file), library_(library), diagnostics_(diagnostics) {}

  std::optional<ResolvedGraph> run() {
    const std::size_t errorsBefore = diagnostics_.errorCount();
    result_.name = graph_.name;
    checkName();
    result_.nodes.resize(graph_.nodes.size());
    for (std::size_t i = 0; i < graph_.nodes.size(); ++i)
      bindNode(i);
    for (std::size_t i = 0; i < graph_.nodes.size(); ++i) {
      if (result_.nodes[i].type)
        bindInputs(i);
    }
    if (diagnostics_.errorCount() > errorsBefore)
      return std::nullopt;
    return std::move(result_);
  }

 private:
  void checkName() {
    const auto& name = graph_.name;
    if (name.size() > kMaxMaterialNameLength) {
      auto& d = diagnostics_.error(file_, graph_.nameLocation,
                                   "the material name is " + std::to_string(name.size()) +
                                       " characters long, over the limit of " +
                                       std::to_string(kMaxMaterialNameLength));
      d.notes.push_back(
          "it names the output files <name>.glsl, <name>.hlsl and <name>.json, and "
          "file names have at most 255 bytes; shorten it (`material Name;`)");
    } else if (name.find("__") != std::string::npos || name.starts_with("gl_")) {
      diagnostics_.error(
          file_, graph_.nameLocation,
          "material name '" + name + "' is reserved in GLSL (no '__', no 'gl_' prefix)");
    }
  }

  void bindNode(std::size_t index) {
    const Node& node = graph_.nodes[index];
    const NodeType* type = library_.find(node.type);
    if (!type) {
      // Its links are already wrong once; consumers need not report them again.
      for (const auto& binding : node.outputs)
        brokenLinks_.insert(binding.link);
      const bool kept = diagnostics_.keeps(file_);
      auto& d = diagnostics_.error(file_, node.location, "unknown node type '" + node.type + "'");
      if (!kept)
        return;
      const auto suggestions = library_.suggestions(node.type);
      if (!suggestions.empty()) {
        std::string list;
        for (const auto& s : suggestions)
          list += (list.empty() ? "'" : ", '") + s + "'";
        d.notes.push_back("did you mean " + list + "?");
      }
      d.notes.push_back("`memograph nodes` lists every node type");
      return;
    }
    ResolvedNode& resolved = result_.nodes[index];
    resolved.type = type;
    resolved.source = &node;
    resolved.inputs.resize(type->sockets.size());
    resolved.outputLinks.resize(type->sockets.size());
    resolved.consumers.resize(type->sockets.size());
    for (const auto& binding : node.outputs) {
      const int socket = socketOf(*type, binding.socket, Direction::Out, binding.location);
      if (socket < 0) {
        brokenLinks_.insert(binding.link);
        continue;
      }
      if (resolved.outputLinks[socket]) {
        diagnostics_.error(file_, binding.location,
                           "output '" + binding.socket + "' is bound twice on this node");
        continue;
      }
      resolved.outputLinks[socket] = binding.link;
      const auto [existing, inserted] =
          producers_.emplace(binding.link, std::pair(index, static_cast<std::size_t>(socket)));
      if (!inserted) {
        const Node& other = graph_.nodes[existing->second.first];
        auto& d = diagnostics_.error(file_, binding.location,
                                     "link " + std::to_string(binding.link) +
                                         " is produced twice; each link has exactly one producer");
        d.notes.push_back("first produced by '" + other.type + "' at " + file_.path + ":" +
                          std::to_string(other.location.line) + ":" +
                          std::to_string(other.location.column));
      }
    }
  }

  // The socket index for `name`, reporting a missing or wrong-direction socket.
  int socketOf(const NodeType& type, const std::string& name, Direction direction,
               SourceLocation at) {
    const int socket = type.socketIndex(name);
    const bool isInput = direction == Direction::In;
    if (socket < 0) {
      auto& d = diagnostics_.error(file_, at,
                                   "'" + type.name + "' has no " + (isInput ? "input" : "output") +
                                       " socket '" + name + "'");
      d.notes.push_back("its inputs: " + socketList(type, Direction::In));
      d.notes.push_back("its outputs: " + socketList(type, Direction::Out));
      return -1;
    }
    if (type.sockets[socket].direction != direction) {
      diagnostics_.error(file_, at,
                         "'" + name + "' is an " + (isInput ? "output" : "input") + " of '" +
                             type.name + "'; write " + name + (isInput ? ">id" : "<id"));
      return -1;
    }
    return socket;
  }

  void bindInputs(std::size_t index) {
    const Node& node = graph_.nodes[index];
    ResolvedNode& resolved = result_.nodes[index];
    const NodeType& type = *resolved.type;
    const std::size_t errorsBefore = diagnostics_.errorCount();
    auto alreadyBound = [&](int socket, SourceLocation at) {
      if (!resolved.inputs[socket])
        return false;
      diagnostics_.error(file_, at,
                         "input '" + type.sockets[socket].name + "' is bound twice on this node");
      return true;
    };
    for (const auto& binding : node.inputs) {
      const int socket = socketOf(type, binding.socket, Direction::In, binding.location);
      if (socket < 0 || alreadyBound(socket, binding.location))
        continue;
      const auto producer = producers_.find(binding.link);
      if (producer == producers_.end() && brokenLinks_.contains(binding.link)) {
        // Reported where the link is produced; mark the input bound to say nothing more.
        resolved.inputs[socket] = InputSource{InputSource::Kind::Default, 0, 0, 0, {}, {}};
        continue;
      }
      if (producer == producers_.end()) {
        auto& d = diagnostics_.error(
            file_, binding.location,
            "link " + std::to_string(binding.link) + " is used here but no node produces it");
        d.notes.push_back("produce it with an output socket: Out>" + std::to_string(binding.link));
        continue;
      }
      InputSource source;
      source.kind = InputSource::Kind::Link;
      source.producer = producer->second.first;
      source.producerSocket = producer->second.second;
      source.link = binding.link;
      source.location = binding.location;
      resolved.inputs[socket] = source;
      result_.nodes[source.producer].consumers[source.producerSocket].push_back(
          Consumer{index, static_cast<std::size_t>(socket)});
    }
    for (const auto& binding : node.constants) {
      const int socket = socketOf(type, binding.socket, Direction::In, binding.location);
      if (socket < 0 || alreadyBound(socket, binding.location))
        continue;
      bindConstant(resolved, socket, binding.value, InputSource::Kind::Constant);
    }
    bindPositional(node, resolved);
    // A misspelt socket or a rejected value usually *is* the missing input: say it once.
    if (diagnostics_.errorCount() > errorsBefore)
      return;
    for (std::size_t socket = 0; socket < type.sockets.size(); ++socket) {
      if (type.sockets[socket].direction != Direction::In || resolved.inputs[socket])
        continue;
      const auto fallback = type.defaults.find(type.sockets[socket].name);
      if (fallback == type.defaults.end()) {
        auto& d = diagnostics_.error(file_, node.location,
                                     "input '" + type.sockets[socket].name + "' of '" + type.name +
                                         "' is not connected and has no default");
        d.notes.push_back("connect it (" + type.sockets[socket].name + "<id) or give it a value (" +
                          type.sockets[socket].name + "=…)");
        continue;
      }
      Literal value = fallback->second;
      value.location = node.location;
      bindConstant(resolved, static_cast<int>(socket), value, InputSource::Kind::Default);
    }
  }

  // Bare literals fill the free input sockets in declaration order. Several numbers for a
  // node with a single free input form one tuple: `Float3Constant 1 0 0 Out>1`.
  void bindPositional(const Node& node, ResolvedNode& resolved) {
    if (node.positional.empty())
      return;
    const NodeType& type = *resolved.type;
    std::vector<int> freeSockets;
    for (std::size_t socket = 0; socket < type.sockets.size(); ++socket) {
      if (type.sockets[socket].direction == Direction::In && !resolved.inputs[socket]) {
        freeSockets.push_back(static_cast<int>(socket));
      }
    }
    // A copy only when several numbers become one tuple: the node's list may be long.
    std::vector<Literal> tupleValue;
    const std::vector<Literal>* valuesPointer = &node.positional;
    const auto& values = node.positional;
    const bool allNumbers = std::all_of(values.begin(), values.end(), [](const Literal& l) {
      return l.kind == Literal::Kind::Number;
    });
    const auto socketTakesWidth = [&](int socket, std::size_t width) {
      return std::any_of(type.overloads.begin(), type.overloads.end(), [&](const Overload& o) {
        return static_cast<std::size_t>(o.socketTypes[socket].width()) == width;
      });
    };
    if (freeSockets.size() == 1 && values.size() >= 2 && values.size() <= 4 && allNumbers &&
        socketTakesWidth(freeSockets[0], values.size())) {
      Literal tuple;
      tuple.kind = Literal::Kind::Tuple;
      tuple.location = values[0].location;
      for (const auto& v : values)
        tuple.components.push_back(v.components[0]);
      tupleValue = {tuple};
      valuesPointer = &tupleValue;
    }
    const auto& bound = *valuesPointer;
    for (std::size_t i = 0; i < bound.size(); ++i) {
      if (i >= freeSockets.size()) {
        auto& d = diagnostics_.error(file_, bound[i].location,
                                     "too many values for '" + type.name + "': its inputs are " +
                                         socketList(type, Direction::In));
        d.notes.push_back("name the socket a value is for: Socket=value");
        return;
      }
      bindConstant(resolved, freeSockets[i], bound[i], InputSource::Kind::Constant);
    }
  }

  void bindConstant(ResolvedNode& resolved, int socket, const Literal& value,
                    InputSource::Kind kind) {
    const NodeType& type = *resolved.type;
    const std::string& name = type.sockets[socket].name;
    const bool wantsTexture = isTextureSocket(type, socket);
    if (wantsTexture != (value.kind == Literal::Kind::String)) {
      diagnostics_.error(file_, value.location,
                         wantsTexture ? "input '" + name + "' of '" + type.name +
                                            "' takes a texture path in quotes, e.g. \"wood.png\""
                                      : "input '" + name + "' of '" + type.name +
                                            "' takes a number or a (x, y, …) tuple, not a string");
      return;
    }
    const bool wantsTable = isTableSocket(type, socket);
    if (wantsTable != (value.kind == Literal::Kind::Table)) {
      diagnostics_.error(
          file_, value.location,
          wantsTable ? "input '" + name + "' of '" + type.name + "' takes a table: [ " +
                           std::to_string(kTableNumbers) + " numbers ] (" +
                           std::to_string(kTableEntries) + " RGBA entries)"
                     : "input '" + name + "' of '" + type.name + "' does not take a [table]");
      return;
    }
    if (wantsTexture && value.text.empty()) {
      // An empty path would resolve to the graph's folder and fail later as "is a folder".
      diagnostics_.error(file_, value.location,
                         "input '" + name + "' of '" + type.name +
                             "' has an empty texture path; name an image file, e.g. \"wood.png\"");
      return;
    }
    if (isIntSocket(type, socket) && !isShaderInt(value)) {
      diagnostics_.error(
          file_, value.location,
          "input '" + name + "' of '" + type.name +
              "' takes a whole number from -2147483648 to 2147483647 (a shader int)");
      return;
    }
    InputSource source;
    source.kind = kind;
    source.constant = value;
    source.location = value.location;
    if (wantsTexture) {
      // Slots are numbered in order of first mention; the same path shares a slot.
      const auto [slot, added] = textureSlots_.emplace(value.text, result_.textures.size());
      source.constant.components = {static_cast<double>(slot->second)};
      if (added)
        result_.textures.push_back(value.text);
    }
    resolved.inputs[socket] = source;
  }

  const Graph& graph_;
  const SourceFile& file_;
  const NodeLibrary& library_;
  Diagnostics& diagnostics_;
  ResolvedGraph result_;
  std::map<std::int64_t, std::pair<std::size_t, std::size_t>> producers_;  // link → node, socket
  std::set<std::int64_t> brokenLinks_;  // produced by a node or socket that does not exist
  // Texture path → slot; a linear search of ResolvedGraph::textures was quadratic.
  std::map<std::string, std::size_t, std::less<>> textureSlots_;
};

}  // namespace

std::optional<ResolvedGraph> resolveGraph(const Graph& graph, const SourceFile& file,
                                          const NodeLibrary& library, Diagnostics& diagnostics) {
  return Resolver(graph, file, library, diagnostics).run();
}

}  // namespace memograph::compiler
