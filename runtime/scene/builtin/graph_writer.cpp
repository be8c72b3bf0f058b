#include "runtime/scene/builtin/graph_writer.h"

#include <cmath>
#include <cstdio>

namespace memograph::runtime {

std::string formatGraphNumber(float value) {
  if (value == 0.0f || !std::isfinite(value))
    return "0.0";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", static_cast<double>(value));
  std::string s = buffer;
  while (s.back() == '0')
    s.pop_back();
  if (s.back() == '.')
    s += '0';
  if (s == "-0.0")
    s = "0.0";
  return s;
}

namespace {

// "(x, y, …)"; built by appending, which also keeps GCC 12's -Wrestrict false positive
// (bug 105329) away from operator+ chains.
std::string formatTuple(std::initializer_list<float> values) {
  std::string out = "(";
  for (float v : values) {
    if (out.size() > 1)
      out += ", ";
    out += formatGraphNumber(v);
  }
  out += ')';
  return out;
}

}  // namespace

GraphArg GraphArg::in(std::string socket, GraphLink link) {
  return {Kind::In, std::move(socket), link, {}};
}
GraphArg GraphArg::out(std::string socket, GraphLink link) {
  return {Kind::Out, std::move(socket), link, {}};
}
GraphArg GraphArg::constant(std::string socket, float value) {
  return {Kind::Constant, std::move(socket), {}, formatGraphNumber(value)};
}
GraphArg GraphArg::constant(std::string socket, int value) {
  return {Kind::Constant, std::move(socket), {}, std::to_string(value)};
}

GraphArg GraphArg::constant(std::string socket, glm::vec2 value) {
  return {Kind::Constant, std::move(socket), {}, formatTuple({value.x, value.y})};
}
GraphArg GraphArg::constant(std::string socket, glm::vec3 value) {
  return {Kind::Constant, std::move(socket), {}, formatTuple({value.x, value.y, value.z})};
}

GraphWriter::GraphWriter(std::string materialName) : name_(std::move(materialName)) {}

void GraphWriter::node(std::string_view type, const std::vector<GraphArg>& args) {
  std::string line(type);
  for (const GraphArg& a : args) {
    line += ' ';
    line += a.socket;
    switch (a.kind) {
      case GraphArg::Kind::In:
        line += '<' + std::to_string(a.link.id);
        break;
      case GraphArg::Kind::Out:
        line += '>' + std::to_string(a.link.id);
        break;
      case GraphArg::Kind::Constant:
        line += '=' + a.literal;
        break;
    }
  }
  line += ';';
  lines_.push_back(std::move(line));
}

std::string GraphWriter::text() const {
  std::string out = "material " + name_ + ";\n";
  for (const std::string& line : lines_)
    out += line + '\n';
  return out;
}

}  // namespace memograph::runtime
