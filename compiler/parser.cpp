#include "compiler/parser.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <optional>

#include "compiler/lexer.h"
#include "compiler/types.h"

namespace memograph::compiler {

namespace {

// Past this many errors a file is probably not a graph at all; stop before flooding.
constexpr std::size_t kMaxErrorsPerFile = 20;

class Parser {
 public:
  Parser(const SourceFile& file, Diagnostics& diagnostics)
      : file_(file), diagnostics_(diagnostics), lexer_(file.text), current_(lexer_.next()) {}

  Graph run() {
    Graph graph;
    graph.name = materialNameFromPath(file_.path);
    while (peek().kind != TokenKind::End && !stopped_) {
      if (errors_ >= kMaxErrorsPerFile) {
        diagnostics_.error(file_, peek().location, "too many errors; giving up on this file");
        break;
      }
      if (!statement(graph) && !stopped_)
        skipPastSemicolon();
    }
    return graph;
  }

 private:
  // The parser looks at most one token past the current one, so it holds two, not the file's.
  const Token& peek() const { return current_; }
  const Token& peekSecond() {
    if (!lookahead_)
      lookahead_ = lexer_.next();
    return *lookahead_;
  }
  Token take() {
    const Token token = current_;
    if (current_.kind != TokenKind::End) {
      current_ = lookahead_ ? *lookahead_ : lexer_.next();
      lookahead_.reset();
    }
    lastTakenLine_ = token.location.line;
    return token;
  }

  void error(const Token& at, std::string message) {
    ++errors_;
    if (at.kind == TokenKind::Invalid) {
      diagnostics_.error(file_, at.location, invalidTokenMessage(at));
    } else {
      diagnostics_.error(file_, at.location, std::move(message));
    }
  }

  // Past a limit the parse stops: what memory and time a graph costs grows with these counts.
  void overLimit(const Token& at, std::string_view what, std::size_t limit) {
    ++errors_;
    diagnostics_.error(file_, at.location,
                       "the graph has more than " + std::to_string(limit) + " " +
                           std::string(what) + ", over the limit (docs/guide/limits.md)");
    stopped_ = true;
  }

  void skipPastSemicolon() {
    while (peek().kind != TokenKind::End && peek().kind != TokenKind::Semicolon)
      take();
    if (peek().kind == TokenKind::Semicolon)
      take();
  }

  bool statement(Graph& graph) {
    const Token head = peek();
    if (head.kind != TokenKind::Identifier) {
      error(head, "expected a node type at the start of a statement, found " +
                      std::string(tokenKindName(head.kind)));
      return false;
    }
    // No node type is called `material`: whatever follows it is meant as the name.
    if (head.text == "material" && peekSecond().kind != TokenKind::Semicolon &&
        peekSecond().kind != TokenKind::Less && peekSecond().kind != TokenKind::Greater &&
        peekSecond().kind != TokenKind::Equals) {
      return materialDeclaration(graph);
    }
    if (graph.nodes.size() == kMaxGraphNodes) {
      overLimit(head, "nodes", kMaxGraphNodes);
      return false;
    }
    Node node;
    node.type = std::string(take().text);
    node.location = head.location;
    while (peek().kind != TokenKind::Semicolon) {
      if (!item(node))
        return false;
    }
    take();  // ';'
    graph.nodes.push_back(std::move(node));
    return true;
  }

  bool materialDeclaration(Graph& graph) {
    take();  // 'material'
    const Token name = take();
    if (name.kind != TokenKind::Identifier) {
      error(name, "'" + std::string(name.text) +
                      "' is not a valid material name: a name starts with a letter or '_' and "
                      "has only letters, digits and '_' (it names EvaluateMaterial_<name> and "
                      "the output files)");
      return false;
    }
    graph.name = std::string(name.text);
    graph.nameLocation = name.location;
    if (peek().kind != TokenKind::Semicolon) {
      error(peek(), "expected ';' after the material name, found " +
                        std::string(tokenKindName(peek().kind)));
      return false;
    }
    take();
    return true;
  }

  bool item(Node& node) {
    const Token token = peek();
    if (items_ == kMaxGraphItems && token.kind != TokenKind::End) {
      overLimit(token, "sockets and values", kMaxGraphItems);
      return false;
    }
    ++items_;
    switch (token.kind) {
      case TokenKind::Identifier:
        return socketBinding(node);
      case TokenKind::Number:
      case TokenKind::String:
      case TokenKind::LeftParen:
      case TokenKind::LeftBracket: {
        Literal value;
        if (!literal(value))
          return false;
        node.positional.push_back(std::move(value));
        return true;
      }
      case TokenKind::End:
        error(token, "missing ';' at the end of the '" + node.type + "' node");
        return false;
      default:
        error(token, "expected a socket (Name<id, Name>id, Name=value) or a value, found " +
                         std::string(tokenKindName(token.kind)));
        return false;
    }
  }

  bool socketBinding(Node& node) {
    const std::uint32_t lineBefore = lastTakenLine_;
    const Token socket = take();
    const Token op = peek();
    if (op.kind == TokenKind::Less || op.kind == TokenKind::Greater) {
      take();
      std::int64_t link = 0;
      if (!linkId(link))
        return false;
      LinkBinding binding{std::string(socket.text), link, socket.location};
      (op.kind == TokenKind::Less ? node.inputs : node.outputs).push_back(binding);
      return true;
    }
    if (op.kind == TokenKind::Equals) {
      take();
      ConstantBinding binding{std::string(socket.text), {}, socket.location};
      if (!literal(binding.value))
        return false;
      node.constants.push_back(std::move(binding));
      return true;
    }
    if (op.kind == TokenKind::Semicolon || op.kind == TokenKind::Identifier) {
      const std::string name(socket.text);
      error(socket, "socket '" + name + "' is not bound: write " + name + "<id (input), " + name +
                        ">id (output) or " + name + "=value");
      // A name opening a new line is more likely the next node after a forgotten ';'.
      if (lineBefore > 0 && lineBefore < socket.location.line) {
        diagnostics_.last().notes.push_back("or is a ';' missing at the end of the line above?");
      }
    } else {
      error(op, "expected '<', '>' or '=' after socket '" + std::string(socket.text) + "', found " +
                    std::string(tokenKindName(op.kind)));
    }
    return false;
  }

  bool linkId(std::int64_t& link) {
    const Token token = peek();
    if (token.kind != TokenKind::Number) {
      error(token, "expected a link id (a whole number) after '<' or '>', found " +
                       std::string(tokenKindName(token.kind)));
      return false;
    }
    take();
    const char* begin = token.text.data();
    const char* end = begin + token.text.size();
    const auto [rest, status] = std::from_chars(begin, end, link);
    if (status != std::errc() || rest != end || link < 0) {
      error(token, "link id '" + std::string(token.text) +
                       "' is not a whole number between 0 and 9223372036854775807");
      return false;
    }
    return true;
  }

  bool number(const Token& token, double& value, bool& isInteger) {
    const std::string text(token.text);
    const char* begin = text.c_str();
    const char* end = begin + text.size();
    if (*begin == '+')
      ++begin;
    const auto [rest, status] = std::from_chars(begin, end, value);
    if (status != std::errc() || rest != end || !std::isfinite(value)) {
      error(token, "'" + text + "' is not a valid finite number");
      return false;
    }
    // Shaders compute in 32-bit floats: a larger value would be emitted as "inf".
    if (std::abs(value) > std::numeric_limits<float>::max()) {
      error(token, "'" + text + "' is too large for a 32-bit float (at most 3.4028235e38)");
      return false;
    }
    isInteger = text.find_first_of(".eE") == std::string::npos;
    return true;
  }

  // Takes `token`, the next token and a number, as a tuple's or a table's component (whether
  // it is written as an integer does not matter there).
  bool takeComponent(const Token& token, double& value) {
    take();
    bool isInteger = false;
    return number(token, value, isInteger);
  }

  bool literal(Literal& out) {
    const Token token = peek();
    out.location = token.location;
    if (token.kind == TokenKind::String) {
      take();
      out.kind = Literal::Kind::String;
      out.text = std::string(token.text);
      return true;
    }
    if (token.kind == TokenKind::Number) {
      take();
      out.kind = Literal::Kind::Number;
      double value = 0;
      if (!number(token, value, out.isInteger))
        return false;
      out.components = {value};
      return true;
    }
    if (token.kind == TokenKind::LeftBracket)
      return table(out);
    if (token.kind != TokenKind::LeftParen) {
      error(token, "expected a value (number, (x, y, …) tuple, [table] or \"string\"), found " +
                       std::string(tokenKindName(token.kind)));
      return false;
    }
    take();
    out.kind = Literal::Kind::Tuple;
    while (true) {
      const Token component = peek();
      if (component.kind != TokenKind::Number) {
        error(component, "expected a number in the tuple, found " +
                             std::string(tokenKindName(component.kind)));
        return false;
      }
      double value = 0;
      if (!takeComponent(component, value))
        return false;
      out.components.push_back(value);
      if (peek().kind == TokenKind::Comma) {
        take();
        continue;
      }
      if (peek().kind == TokenKind::RightParen) {
        take();
        break;
      }
      error(peek(),
            "expected ',' or ')' in the tuple, found " + std::string(tokenKindName(peek().kind)));
      return false;
    }
    if (out.components.size() < 2 || out.components.size() > 4) {
      error(token,
            "a tuple has 2 to 4 components; this one has " + std::to_string(out.components.size()));
      return false;
    }
    return true;
  }

  // `[ n n n … ]`: a lookup table of kTableEntries RGBA entries (ramps, curves), numbers
  // separated by white space or commas.
  bool table(Literal& out) {
    const Token open = take();
    out.kind = Literal::Kind::Table;
    while (peek().kind != TokenKind::RightBracket) {
      const Token component = peek();
      if (component.kind == TokenKind::Comma) {
        take();
        continue;
      }
      if (component.kind != TokenKind::Number) {
        error(component, "expected a number or ']' in the table, found " +
                             std::string(tokenKindName(component.kind)));
        return false;
      }
      double value = 0;
      if (!takeComponent(component, value))
        return false;
      // Bounded before the size check so a runaway table costs no more than a full one.
      if (out.components.size() == static_cast<std::size_t>(kTableNumbers)) {
        error(component, "a table has " + std::to_string(kTableNumbers) + " numbers (" +
                             std::to_string(kTableEntries) + " RGBA entries); this one has more");
        return false;
      }
      out.components.push_back(value);
    }
    take();
    if (out.components.size() != static_cast<std::size_t>(kTableNumbers)) {
      error(open, "a table has " + std::to_string(kTableNumbers) + " numbers (" +
                      std::to_string(kTableEntries) + " RGBA entries); this one has " +
                      std::to_string(out.components.size()));
      return false;
    }
    return true;
  }

  const SourceFile& file_;
  Diagnostics& diagnostics_;
  Lexer lexer_;
  Token current_;
  std::optional<Token> lookahead_;
  std::uint32_t lastTakenLine_ = 0;  // of the token take() returned last; 0 before any
  std::size_t errors_ = 0;
  std::size_t items_ = 0;  // socket bindings and values of all nodes so far
  bool stopped_ = false;   // a limit was reached
};

}  // namespace

Graph parseGraph(const SourceFile& file, Diagnostics& diagnostics) {
  return Parser(file, diagnostics).run();
}

std::string materialNameFromPath(std::string_view path) {
  const auto slash = path.find_last_of("/\\");
  std::string_view stem = slash == std::string_view::npos ? path : path.substr(slash + 1);
  const auto dot = stem.find('.');
  if (dot != std::string_view::npos)
    stem = stem.substr(0, dot);
  std::string name;
  for (const char c : stem) {
    name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0])))
    name = "M" + name;
  return name;
}

}  // namespace memograph::compiler
