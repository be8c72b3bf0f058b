// Writes material graphs as .mgraph text (thesis Listing 5.1: `Type Socket<id Socket>id
// Socket=value;`), so that the built-in scenes' materials go through the compiler exactly
// like a user's hand-written graphs.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace memograph::runtime {

// A link id in the graph being written: one producer socket, any number of consumers.
struct GraphLink {
  int id = -1;
};

// One socket binding of a node: an input from a link, an output to a link, or a constant.
struct GraphArg {
  enum class Kind { In, Out, Constant };
  Kind kind = Kind::Constant;
  std::string socket;
  GraphLink link;
  std::string literal;  // Constant: the literal as written in the graph

  static GraphArg in(std::string socket, GraphLink link);
  static GraphArg out(std::string socket, GraphLink link);
  static GraphArg constant(std::string socket, float value);
  static GraphArg constant(std::string socket, int value);
  static GraphArg constant(std::string socket, glm::vec2 value);
  static GraphArg constant(std::string socket, glm::vec3 value);
};

class GraphWriter {
 public:
  explicit GraphWriter(std::string materialName);

  GraphLink newLink() { return GraphLink{nextLink_++}; }
  // Appends `type args…;` as one line, in the order given.
  void node(std::string_view type, const std::vector<GraphArg>& args);

  const std::string& name() const { return name_; }
  // The whole graph: `material Name;` then one node per line.
  std::string text() const;

 private:
  std::string name_;
  std::vector<std::string> lines_;
  int nextLink_ = 0;
};

// Formats a float so the graph parser reads it back as a float (always with a '.') and the
// text is the same on every machine (no locale, fixed precision, trailing zeros trimmed).
std::string formatGraphNumber(float value);

}  // namespace memograph::runtime
