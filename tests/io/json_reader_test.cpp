// The JSON reader (tools/io/json_reader.h): what it accepts, and each refusal with its
// message and byte offset.
#include "tools/io/json_reader.h"

#include <cmath>
#include <optional>
#include <string>

#include <gtest/gtest.h>

namespace memograph::io {
namespace {

using Kind = JsonValue::Kind;

JsonValue read(std::string_view text) {
  JsonError error;
  auto value = readJson(text, error);
  EXPECT_TRUE(value) << text << ": " << error.message << " (at byte " << error.offset << ")";
  return value ? std::move(*value) : JsonValue();
}

// The refusal of `text` as "message (at byte N)", or "accepted".
std::string refusal(std::string_view text, int maxDepth = kMaxJsonDepth,
                    std::size_t maxValues = kMaxJsonValues) {
  JsonError error;
  if (readJson(text, error, maxDepth, maxValues))
    return "accepted";
  return error.message + " (at byte " + std::to_string(error.offset) + ")";
}

TEST(JsonReader, ReadsEveryKindWithItsOffset) {
  const JsonValue root = read(
      " {\"a\": [1, -2.5e1, 0.25, -0, 1E2], \"b\": {\"c\": true}, \"d\": false,\n"
      "\t\"e\": null, \"f\": \"text\"}\r\n");
  ASSERT_EQ(root.kind, Kind::Object);
  EXPECT_EQ(root.offset, 1u);
  ASSERT_EQ(root.members.size(), 5u);
  const JsonValue* a = root.get("a");
  ASSERT_TRUE(a);
  ASSERT_EQ(a->kind, Kind::Array);
  EXPECT_EQ(a->offset, 7u);
  ASSERT_EQ(a->size(), 5u);
  EXPECT_EQ(a->items[0].number, 1.0);
  EXPECT_EQ(a->items[1].number, -25.0);
  EXPECT_EQ(a->items[1].offset, 11u);
  EXPECT_EQ(a->items[2].number, 0.25);
  EXPECT_EQ(a->items[3].number, 0.0);
  EXPECT_TRUE(std::signbit(a->items[3].number));
  EXPECT_EQ(a->items[4].number, 100.0);
  ASSERT_TRUE(root.get("b") && root.get("b")->get("c"));
  EXPECT_EQ(root.get("b")->get("c")->kind, Kind::Bool);
  EXPECT_TRUE(root.get("b")->get("c")->boolean);
  EXPECT_EQ(root.get("d")->kind, Kind::Bool);
  EXPECT_FALSE(root.get("d")->boolean);
  EXPECT_EQ(root.get("e")->kind, Kind::Null);
  EXPECT_EQ(root.get("f")->string, "text");
  EXPECT_EQ(root.get("missing"), nullptr);
  EXPECT_EQ(root.size(), 0u);  // an object has no elements
  EXPECT_EQ(read("[]").size(), 0u);
  EXPECT_EQ(read("{}").members.size(), 0u);
  EXPECT_EQ(read("  7 ").number, 7.0);  // any value may be the root
}

TEST(JsonReader, ResolvesEscapesToUtf8) {
  EXPECT_EQ(read(R"("\" \\ \/ \b \f \n \r \t")").string, "\" \\ / \b \f \n \r \t");
  EXPECT_EQ(read(R"("\u0041\u00e9\u20AC")").string, "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(read(R"("\ud83d\ude00")").string, "\xF0\x9F\x98\x80");  // a surrogate pair
  EXPECT_EQ(read(R"("\u0000")").string, std::string(1, '\0'));
  EXPECT_EQ(read("\"caf\xC3\xA9 \xF0\x9F\x98\x80\"").string, "caf\xC3\xA9 \xF0\x9F\x98\x80");
  // Member names too.
  EXPECT_NE(read(R"({"\u0075ri": 1})").get("uri"), nullptr);
}

TEST(JsonReader, ReadsNumbersBeyondADoublesPrecisionAndTooSmallForIt) {
  EXPECT_EQ(read("1.7976931348623157e308").number, 1.7976931348623157e308);
  EXPECT_EQ(read("123456789012345678901234567890").number, 1.2345678901234568e29);
  EXPECT_EQ(read("1e-400").number, 0.0);
  EXPECT_EQ(read("0.0000000000000000000000000000000000001e-300").number, 0.0);
  EXPECT_TRUE(std::signbit(read("-1e-400").number));
}

TEST(JsonReader, KeepsDuplicateMembersAndFindsThem) {
  const JsonValue root = read(R"({"a": 1, "b": 2, "a": 3, "b": 4})");
  EXPECT_EQ(root.members.size(), 4u);
  EXPECT_EQ(root.get("a")->number, 1.0);  // the first
  EXPECT_EQ(root.repeatedMember(), std::optional<std::size_t>(2));
  EXPECT_EQ(root.members[2].value.offset, 22u);
  EXPECT_EQ(read(R"({"a": 1, "b": {"a": 2}})").repeatedMember(), std::nullopt);
  EXPECT_EQ(read("[1, 1]").repeatedMember(), std::nullopt);
}

TEST(JsonReader, RefusesNestingPastTheLimit) {
  const std::string deepest = std::string(64, '[') + std::string(64, ']');
  EXPECT_EQ(refusal(deepest), "accepted");
  EXPECT_EQ(refusal("[" + deepest + "]"),
            "the JSON is nested more than 64 levels deep, over the limit "
            "(docs/guide/limits.md) (at byte 64)");
  EXPECT_EQ(refusal(R"({"a": {"b": [0]}})", 2),
            "the JSON is nested more than 2 levels deep, over the limit (docs/guide/limits.md) "
            "(at byte 12)");
  // Far past the limit: refused, not a stack overflow.
  EXPECT_NE(refusal(std::string(1000000, '[')).find("nested more than 64"), std::string::npos);
}

// The tree's memory is bounded by its value count, whatever the file's size: at the
// default, 2^23 values of one-digit numbers (16 MiB of text) are refused, not read into a
// tree of about 1 GB.
TEST(JsonReader, RefusesMoreValuesThanTheLimit) {
  EXPECT_EQ(refusal(R"({"a": [0, 1]})", kMaxJsonDepth, 4), "accepted");
  EXPECT_EQ(refusal(R"({"a": [0, 1, 2]})", kMaxJsonDepth, 4),
            "the JSON holds more than 4 values, over the limit (docs/guide/limits.md) (at "
            "byte 13)");
  std::string many = "[0";
  for (std::size_t i = 1; i < kMaxJsonValues; ++i)
    many += ",0";
  many += "]";
  EXPECT_NE(refusal(many).find("holds more than 8388608 values"), std::string::npos);
}

TEST(JsonReader, RefusesBadEscapes) {
  EXPECT_EQ(refusal(R"(["ab\x"])"), "an invalid escape '\\x' in a string (at byte 4)");
  EXPECT_EQ(refusal("[\"\\\x01\"]"),
            "an invalid escape in a string (a backslash, then byte 0x01) (at byte 2)");
  EXPECT_EQ(refusal(R"("\u12G4")"),
            "an invalid \\u escape (it takes four hexadecimal digits) (at byte 1)");
  EXPECT_EQ(refusal(R"("\u12)"),
            "an invalid \\u escape (it takes four hexadecimal digits) (at byte 1)");
}

TEST(JsonReader, RefusesUnpairedSurrogates) {
  EXPECT_EQ(refusal(R"("a\ud83d")"), "an unpaired surrogate in a \\u escape (at byte 2)");
  EXPECT_EQ(refusal(R"("\ud83dx")"), "an unpaired surrogate in a \\u escape (at byte 1)");
  EXPECT_EQ(refusal(R"("\ud83d\u0041")"), "an unpaired surrogate in a \\u escape (at byte 1)");
  EXPECT_EQ(refusal(R"("\ud83d\ud83d")"), "an unpaired surrogate in a \\u escape (at byte 1)");
  EXPECT_EQ(refusal(R"(["\ude00"])"), "an unpaired surrogate in a \\u escape (at byte 2)");
}

TEST(JsonReader, RefusesControlCharactersAndInvalidUtf8InStrings) {
  EXPECT_EQ(refusal("{\"a\": \"line\nbreak\"}"),
            "a control character (byte 0x0a) in a string, where JSON needs an escape (at byte 11)");
  EXPECT_EQ(refusal(std::string("\"\0\"", 3)),
            "a control character (byte 0x00) in a string, where JSON needs an escape (at byte 1)");
  EXPECT_EQ(refusal("\"ab\xC3\x28\""), "invalid UTF-8 in a string (at byte 3)");
  EXPECT_EQ(refusal("\"\xC0\xAF\""), "invalid UTF-8 in a string (at byte 1)");      // overlong
  EXPECT_EQ(refusal("\"\xED\xA0\x80\""), "invalid UTF-8 in a string (at byte 1)");  // a surrogate
  EXPECT_EQ(refusal("\"\xF4\x90\x80\x80\""), "invalid UTF-8 in a string (at byte 1)");  // >U+10FFFF
  EXPECT_EQ(refusal("\"\xE2\x82\""), "invalid UTF-8 in a string (at byte 1)");          // cut short
  EXPECT_EQ(refusal("\"\xE2\x82"), "invalid UTF-8 in a string (at byte 1)");
}

TEST(JsonReader, RefusesTextAfterTheValue) {
  EXPECT_EQ(refusal("{} x"), "text after the JSON value (at byte 3)");
  EXPECT_EQ(refusal("{}{}"), "text after the JSON value (at byte 2)");
  EXPECT_EQ(refusal("1 2"), "text after the JSON value (at byte 2)");
}

TEST(JsonReader, RefusesTruncatedInput) {
  EXPECT_EQ(refusal(""), "unexpected end of the JSON, expected a value (at byte 0)");
  EXPECT_EQ(refusal("  \n"), "unexpected end of the JSON, expected a value (at byte 3)");
  EXPECT_EQ(refusal(R"({"a": [1, 2)"),
            "unexpected end of the JSON, expected ',' or ']' (at byte 11)");
  EXPECT_EQ(refusal(R"({"a": [1, )"), "unexpected end of the JSON, expected a value (at byte 10)");
  EXPECT_EQ(refusal(R"({"a")"), "unexpected end of the JSON, expected ':' (at byte 4)");
  EXPECT_EQ(refusal(R"({"a": 1)"), "unexpected end of the JSON, expected ',' or '}' (at byte 7)");
  EXPECT_EQ(refusal(R"({"a": 1,)"),
            "unexpected end of the JSON, expected a member name (at byte 8)");
  EXPECT_EQ(refusal(R"({"a": "text)"), "an unterminated string (at byte 6)");
  EXPECT_EQ(refusal(R"(["text\)"), "an unterminated string (at byte 1)");
  EXPECT_EQ(refusal("tru"), "expected 'true' (at byte 0)");
  EXPECT_EQ(refusal("[nul"), "expected 'null' (at byte 1)");
  EXPECT_EQ(refusal("-"), "an invalid number (no digit after '-') (at byte 0)");
  EXPECT_EQ(refusal("1."), "an invalid number (no digit after '.') (at byte 0)");
  EXPECT_EQ(refusal("[1e"), "an invalid number (no digit in the exponent) (at byte 1)");
}

TEST(JsonReader, RefusesWhatIsNotJsonsGrammar) {
  EXPECT_EQ(refusal("[1,]"), "expected a value, found ']' (at byte 3)");
  EXPECT_EQ(refusal(R"({"a": 1,})"), "expected a member name, found '}' (at byte 8)");
  EXPECT_EQ(refusal("{1: 2}"), "expected a member name, found '1' (at byte 1)");
  EXPECT_EQ(refusal("{'a': 2}"), "expected a member name, found \"'\" (at byte 1)");
  EXPECT_EQ(refusal(R"({"a" 1})"), "expected ':', found '1' (at byte 5)");
  EXPECT_EQ(refusal("[1 2]"), "expected ',' or ']', found '2' (at byte 3)");
  EXPECT_EQ(refusal("+1"), "expected a value, found '+' (at byte 0)");
  EXPECT_EQ(refusal(".5"), "expected a value, found '.' (at byte 0)");
  EXPECT_EQ(refusal("012"), "an invalid number (a leading zero) (at byte 0)");
  EXPECT_EQ(refusal("[-1e400]"),
            "a number beyond the range of a double (about 1.8e308) (at byte 1)");
  EXPECT_EQ(refusal("1" + std::string(400, '0')),
            "a number beyond the range of a double (about 1.8e308) (at byte 0)");
  EXPECT_EQ(refusal("NaN"), "expected a value, found 'N' (at byte 0)");
  EXPECT_EQ(refusal("[Infinity]"), "expected a value, found 'I' (at byte 1)");
  EXPECT_EQ(refusal("\xEF\xBB\xBF{}"), "expected a value, found byte 0xef (at byte 0)");  // a BOM
  EXPECT_EQ(refusal("\v1"), "expected a value, found byte 0x0b (at byte 0)");
}

}  // namespace
}  // namespace memograph::io
