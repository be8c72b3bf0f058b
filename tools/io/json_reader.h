// The project's JSON reader: strict RFC 8259 and bounded, for the JSON memograph reads from
// files it did not write (glTF scenes, the Blender exporter's index.json). The C++ standard
// library only, so every build has it, the GPU bundle's CLI included (its library,
// memograph_json, depends on nothing).
//
// What it accepts is exactly one JSON text:
//  - arrays and objects nested at most `maxDepth` deep, so the recursion is bounded, and at
//    most `maxValues` values in all, so the tree's memory is;
//  - strings of valid UTF-8 without raw control characters, their escapes resolved to
//    UTF-8 (\uXXXX surrogate pairs joined; a surrogate without its pair refused);
//  - numbers in JSON's grammar (no '+', no leading zero, no bare '.'), read as doubles; one
//    beyond a double's range is refused, one too small for it is read as 0;
//  - true, false and null;
//  - whitespace around tokens, and nothing after the value.
// Anything else is an error naming what is wrong and its byte offset in the text.
// Duplicate member names are kept (RFC 8259 leaves their meaning open); a schema that
// forbids them asks JsonValue::repeatedMember.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace memograph::io {

// The nesting limit of arrays and objects (docs/guide/limits.md): far deeper than a glTF
// or index.json needs, and shallow enough that the reader's recursion cannot exhaust the
// stack.
inline constexpr int kMaxJsonDepth = 64;
// The most values one text may hold. Each costs about 100 bytes in the tree against as few
// as 2 bytes of text ("0,"), so a 1 GiB scene file of small numbers would take some 50 GB;
// 2^23 values bound the tree near 1 GB. A glTF's JSON holds its scene graph, not its vertex
// data (that is in binary buffers), so real files stay far below it.
inline constexpr std::size_t kMaxJsonValues = std::size_t(1) << 23;

struct JsonMember;

// One JSON value; which fields mean anything depends on `kind`.
struct JsonValue {
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;             // Bool
  double number = 0.0;              // Number
  std::string string;               // String, escapes resolved (UTF-8)
  std::vector<JsonValue> items;     // Array, in order
  std::vector<JsonMember> members;  // Object, in the text's order, duplicates included
  std::size_t offset = 0;           // where the value starts in the text, for messages

  // The first member named `key`; null when there is none or this is not an object.
  const JsonValue* get(std::string_view key) const;
  // An array's element count; 0 for any other kind.
  std::size_t size() const;
  // The index in `members` of the first member whose name an earlier member has, if any.
  std::optional<std::size_t> repeatedMember() const;
};

struct JsonMember {
  std::string key;  // escapes resolved (UTF-8)
  JsonValue value;
};

struct JsonError {
  std::string message;     // what is wrong, e.g. "an unpaired surrogate in a \u escape"
  std::size_t offset = 0;  // where, as a byte offset in the text
};

// Reads `text` as one JSON value; nullopt with `error` set when it is not one.
std::optional<JsonValue> readJson(std::string_view text, JsonError& error,
                                  int maxDepth = kMaxJsonDepth,
                                  std::size_t maxValues = kMaxJsonValues);

}  // namespace memograph::io
