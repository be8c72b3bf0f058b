#include "runtime/vk/spirv_size.h"

#include <map>
#include <stdexcept>

namespace memograph::runtime {

namespace {

constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kOpName = 5;
constexpr std::uint32_t kOpEntryPoint = 15;
constexpr std::uint32_t kOpFunction = 54;
constexpr std::uint32_t kOpFunctionEnd = 56;
constexpr std::uint32_t kOpFunctionCall = 57;

// A module's call graph: per function id its own instructions and its calls by callee.
struct CallGraph {
  struct Function {
    std::uint64_t instructions = 0;
    std::map<std::uint32_t, std::uint64_t> calls;  // callee id -> call sites
  };
  std::map<std::uint32_t, Function> functions;
  std::vector<std::uint32_t> entryPoints;
  // OpName up to the '(' where glslang's names of functions go on with the parameters' types
  // -> ids (functions and others).
  std::multimap<std::string, std::uint32_t> names;
};

std::string literalString(const std::vector<std::uint32_t>& spirv, std::size_t word,
                          std::size_t end) {
  std::string text;
  for (; word < end; ++word)
    for (int byte = 0; byte < 4; ++byte) {
      const char c = static_cast<char>((spirv[word] >> (8 * byte)) & 0xffu);
      if (c == '\0')
        return text;
      text += c;
    }
  return text;
}

CallGraph readCallGraph(const std::vector<std::uint32_t>& spirv) {
  if (spirv.size() < 5 || spirv[0] != kMagic)
    throw std::invalid_argument("spirvSize: not a SPIR-V module (no magic number)");
  CallGraph graph;
  CallGraph::Function* current = nullptr;
  for (std::size_t word = 5; word < spirv.size();) {
    const std::uint32_t count = spirv[word] >> 16;
    const std::uint32_t opcode = spirv[word] & 0xffffu;
    if (count == 0 || word + count > spirv.size())
      throw std::invalid_argument("spirvSize: a truncated instruction at word " +
                                  std::to_string(word));
    if (opcode == kOpName && count >= 3) {
      const std::string name = literalString(spirv, word + 2, word + count);
      graph.names.emplace(name.substr(0, name.find('(')), spirv[word + 1]);
    } else if (opcode == kOpEntryPoint && count >= 3)
      graph.entryPoints.push_back(spirv[word + 2]);
    else if (opcode == kOpFunction && count >= 3)
      current = &graph.functions[spirv[word + 2]];
    if (current) {
      ++current->instructions;
      if (opcode == kOpFunctionCall && count >= 4)
        ++current->calls[spirv[word + 3]];
    }
    if (opcode == kOpFunctionEnd)
      current = nullptr;
    word += count;
  }
  for (const auto& [id, function] : graph.functions)
    for (const auto& [callee, sites] : function.calls)
      if (!graph.functions.count(callee))
        throw std::invalid_argument("spirvSize: a call of function %" + std::to_string(callee) +
                                    ", which the module does not define");
  return graph;
}

// Instructions of `id` with every call inlined (SPIR-V forbids recursion: the graph is acyclic).
std::uint64_t inlined(const CallGraph& graph, std::uint32_t id,
                      std::map<std::uint32_t, std::uint64_t>& memo) {
  if (auto found = memo.find(id); found != memo.end())
    return found->second;
  const CallGraph::Function& function = graph.functions.at(id);
  std::uint64_t total = function.instructions;
  for (const auto& [callee, sites] : function.calls)
    total += sites * inlined(graph, callee, memo);
  memo[id] = total;
  return total;
}

// Copies of `target` inside `id` with every call inlined.
std::uint64_t copiesWithin(const CallGraph& graph, std::uint32_t id, std::uint32_t target,
                           std::map<std::uint32_t, std::uint64_t>& memo) {
  if (auto found = memo.find(id); found != memo.end())
    return found->second;
  std::uint64_t total = 0;
  for (const auto& [callee, sites] : graph.functions.at(id).calls)
    total += sites * (callee == target ? 1 : copiesWithin(graph, callee, target, memo));
  memo[id] = total;
  return total;
}

}  // namespace

SpirvSize spirvSize(const std::vector<std::uint32_t>& spirv) {
  const CallGraph graph = readCallGraph(spirv);
  SpirvSize size;
  for (const auto& [id, function] : graph.functions)
    size.instructions += function.instructions;
  std::map<std::uint32_t, std::uint64_t> memo;
  for (std::uint32_t entry : graph.entryPoints)
    if (graph.functions.count(entry))
      size.inlinedInstructions += inlined(graph, entry, memo);
  return size;
}

SpirvFunctionCopies spirvFunctionCopies(const std::vector<std::uint32_t>& spirv,
                                        const std::string& name) {
  const CallGraph graph = readCallGraph(spirv);
  SpirvFunctionCopies result;
  std::uint32_t target = 0;
  bool found = false;
  const auto [first, last] = graph.names.equal_range(name);
  for (auto named = first; named != last && !found; ++named)
    if (graph.functions.count(named->second)) {
      target = named->second;
      found = true;
    }
  if (!found)
    return result;
  std::map<std::uint32_t, std::uint64_t> copiesMemo;
  for (std::uint32_t entry : graph.entryPoints)
    if (graph.functions.count(entry))
      result.copies += entry == target ? 1 : copiesWithin(graph, entry, target, copiesMemo);
  if (result.copies > 0) {
    std::map<std::uint32_t, std::uint64_t> memo;
    result.inlinedInstructions = inlined(graph, target, memo);
  }
  return result;
}

}  // namespace memograph::runtime
