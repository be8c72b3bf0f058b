#include "compiler/schedule.h"

#include <algorithm>

namespace memograph::compiler {

namespace {

enum class Mark { Unvisited, InProgress, Done };

std::string describe(const ResolvedGraph& graph, const SourceFile& file, std::size_t node) {
  const auto& at = graph.nodes[node].source->location;
  return "'" + graph.nodes[node].type->name + "' at " + file.path + ":" + std::to_string(at.line) +
         ":" + std::to_string(at.column);
}

}  // namespace

std::optional<std::vector<std::size_t>> scheduleGraph(const ResolvedGraph& graph,
                                                      const SourceFile& file,
                                                      Diagnostics& diagnostics) {
  std::vector<std::size_t> sinks;
  for (std::size_t i = 0; i < graph.nodes.size(); ++i) {
    if (graph.nodes[i].type->isSink)
      sinks.push_back(i);
  }
  if (sinks.empty()) {
    auto& d = diagnostics.error(file, SourceLocation{1, 1},
                                "the graph has no output node, so it computes nothing");
    d.notes.push_back("add one, e.g. `BaseColorOutput In<1;` (`memograph nodes` lists them)");
    return std::nullopt;
  }

  // Iterative DFS (graphs can be deep chains): each frame is a node and the next input
  // socket to visit. Post-order gives producers before consumers.
  std::vector<Mark> marks(graph.nodes.size(), Mark::Unvisited);
  std::vector<std::size_t> order;
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  for (const std::size_t sink : sinks) {
    if (marks[sink] != Mark::Unvisited)
      continue;
    stack.emplace_back(sink, 0);
    marks[sink] = Mark::InProgress;
    while (!stack.empty()) {
      auto& [node, nextSocket] = stack.back();
      const auto& inputs = graph.nodes[node].inputs;
      bool descended = false;
      while (nextSocket < inputs.size()) {
        const auto& input = inputs[nextSocket++];
        if (!input || input->kind != InputSource::Kind::Link)
          continue;
        const std::size_t producer = input->producer;
        if (marks[producer] == Mark::InProgress) {
          // The stack from `producer` to the top is the cycle.
          auto start = std::find_if(stack.begin(), stack.end(),
                                    [&](const auto& frame) { return frame.first == producer; });
          auto& d = diagnostics.error(file, input->location,
                                      "link " + std::to_string(input->link) +
                                          " closes a cycle; material graphs must be acyclic");
          std::string path;
          for (auto it = stack.end(); it != start;) {
            --it;
            path += describe(graph, file, it->first) + " → ";
          }
          d.notes.push_back("cycle: " + path + describe(graph, file, node));
          return std::nullopt;
        }
        if (marks[producer] == Mark::Unvisited) {
          marks[producer] = Mark::InProgress;
          stack.emplace_back(producer, 0);
          descended = true;
          break;
        }
      }
      if (descended)
        continue;
      marks[node] = Mark::Done;
      order.push_back(node);
      stack.pop_back();
    }
  }
  for (std::size_t i = 0; i < graph.nodes.size(); ++i) {
    if (marks[i] == Mark::Unvisited) {
      diagnostics.warning(
          file, graph.nodes[i].source->location,
          "'" + graph.nodes[i].type->name + "' does not reach any output node; it is left out");
    }
  }
  return order;
}

}  // namespace memograph::compiler
