#include "tools/io/json_reader.h"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <system_error>
#include <unordered_set>

namespace memograph::io {

const JsonValue* JsonValue::get(std::string_view key) const {
  for (const JsonMember& member : members) {
    if (member.key == key)
      return &member.value;
  }
  return nullptr;
}

std::size_t JsonValue::size() const {
  return kind == Kind::Array ? items.size() : 0;
}

std::optional<std::size_t> JsonValue::repeatedMember() const {
  std::unordered_set<std::string_view> seen;
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (!seen.insert(members[i].key).second)
      return i;
  }
  return std::nullopt;
}

namespace {

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

// A byte as a message shows it: the character when printable ASCII, its value otherwise.
std::string shown(char c) {
  if (c == '\'')
    return "\"'\"";
  if (c > ' ' && c < 0x7F)
    return std::string("'") + c + "'";
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "byte 0x%02x", unsigned(static_cast<unsigned char>(c)));
  return buffer;
}

void appendUtf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += char(code);
  } else if (code < 0x800) {
    out += char(0xC0 | (code >> 6));
    out += char(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += char(0xE0 | (code >> 12));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  } else {
    out += char(0xF0 | (code >> 18));
    out += char(0x80 | ((code >> 12) & 0x3F));
    out += char(0x80 | ((code >> 6) & 0x3F));
    out += char(0x80 | (code & 0x3F));
  }
}

// Whether a number (in JSON's grammar) that from_chars found outside a double's range is
// too large rather than too small. The power of ten of its first significant digit tells:
// a double's largest and smallest magnitudes lie some 630 powers of ten apart.
bool tooLarge(std::string_view number) {
  std::size_t i = number[0] == '-' ? 1 : 0;
  long long power = 0;
  if (number[i] != '0') {
    const std::size_t first = i;
    while (i < number.size() && isDigit(number[i]))
      ++i;
    power = static_cast<long long>(i - first) - 1;
  } else if (i + 1 < number.size() && number[i + 1] == '.') {
    i += 2;
    power = -1;
    while (i < number.size() && number[i] == '0') {
      ++i;
      --power;
    }
  }
  while (i < number.size() && number[i] != 'e' && number[i] != 'E')
    ++i;
  if (i < number.size()) {
    ++i;
    const bool negative = number[i] == '-';
    if (number[i] == '-' || number[i] == '+')
      ++i;
    long long exponent = 0;
    for (; i < number.size() && exponent < 1000000; ++i)  // saturates: only the sign matters
      exponent = exponent * 10 + (number[i] - '0');
    power += negative ? -exponent : exponent;
  }
  return power > 0;
}

// Recursive descent; `maxDepth` bounds the recursion.
class Reader {
 public:
  Reader(std::string_view text, int maxDepth, std::size_t maxValues)
      : text_(text), maxDepth_(maxDepth), maxValues_(maxValues) {}

  std::optional<JsonValue> read(JsonError& error) {
    JsonValue root;
    skipSpace();
    if (value(root, 1)) {
      skipSpace();
      if (pos_ == text_.size())
        return root;
      fail("text after the JSON value");
    }
    error = std::move(error_);
    return std::nullopt;
  }

 private:
  bool fail(std::string message, std::size_t at) {
    error_ = {std::move(message), at};
    return false;
  }
  bool fail(std::string message) { return fail(std::move(message), pos_); }
  // "expected X", saying what stands there instead.
  bool expected(const std::string& what) {
    if (pos_ >= text_.size())
      return fail("unexpected end of the JSON, expected " + what);
    return fail("expected " + what + ", found " + shown(text_[pos_]));
  }

  void skipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n' ||
                                   text_[pos_] == '\r' || text_[pos_] == '\t'))
      ++pos_;
  }
  bool take(char c) {
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool digitHere() const { return pos_ < text_.size() && isDigit(text_[pos_]); }

  // A value starting at pos_; `depth` is the nesting level it has if it is an array or object.
  bool value(JsonValue& out, int depth) {
    out.offset = pos_;
    if (++values_ > maxValues_)
      return fail("the JSON holds more than " + std::to_string(maxValues_) +
                  " values, over the limit (docs/guide/limits.md)");
    if (pos_ >= text_.size())
      return expected("a value");
    switch (text_[pos_]) {
      case '{':
        return container(out, JsonValue::Kind::Object, depth);
      case '[':
        return container(out, JsonValue::Kind::Array, depth);
      case '"':
        out.kind = JsonValue::Kind::String;
        return string(out.string);
      case 't':
        out.boolean = true;
        return literal(out, "true", JsonValue::Kind::Bool);
      case 'f':
        return literal(out, "false", JsonValue::Kind::Bool);
      case 'n':
        return literal(out, "null", JsonValue::Kind::Null);
      default:
        if (text_[pos_] == '-' || isDigit(text_[pos_]))
          return number(out);
        return expected("a value");
    }
  }

  // An array or an object, from its opening bracket.
  bool container(JsonValue& out, JsonValue::Kind kind, int depth) {
    if (depth > maxDepth_)
      return fail("the JSON is nested more than " + std::to_string(maxDepth_) +
                  " levels deep, over the limit (docs/guide/limits.md)");
    out.kind = kind;
    const bool object = kind == JsonValue::Kind::Object;
    const char close = object ? '}' : ']';
    ++pos_;
    skipSpace();
    if (take(close))
      return true;
    for (;;) {
      JsonValue* element = nullptr;
      if (object) {
        if (pos_ >= text_.size() || text_[pos_] != '"')
          return expected("a member name");
        JsonMember& member = out.members.emplace_back();
        if (!string(member.key))
          return false;
        skipSpace();
        if (!take(':'))
          return expected("':'");
        skipSpace();
        element = &member.value;
      } else {
        element = &out.items.emplace_back();
      }
      if (!value(*element, depth + 1))
        return false;
      skipSpace();
      if (take(close))
        return true;
      if (!take(','))
        return expected(object ? "',' or '}'" : "',' or ']'");
      skipSpace();
    }
  }

  bool literal(JsonValue& out, std::string_view word, JsonValue::Kind kind) {
    if (text_.substr(pos_, word.size()) != word)
      return fail("expected '" + std::string(word) + "'");
    out.kind = kind;
    pos_ += word.size();
    return true;
  }

  bool number(JsonValue& out) {
    const std::size_t start = pos_;
    const bool negative = take('-');
    if (take('0')) {
      if (digitHere())
        return fail("an invalid number (a leading zero)", start);
    } else if (digitHere()) {
      while (digitHere())
        ++pos_;
    } else {
      return fail("an invalid number (no digit after '-')", start);
    }
    if (take('.')) {
      if (!digitHere())
        return fail("an invalid number (no digit after '.')", start);
      while (digitHere())
        ++pos_;
    }
    if (take('e') || take('E')) {
      if (!take('+'))
        take('-');
      if (!digitHere())
        return fail("an invalid number (no digit in the exponent)", start);
      while (digitHere())
        ++pos_;
    }
    out.kind = JsonValue::Kind::Number;
    const char* first = text_.data() + start;
    const auto [end, ec] = std::from_chars(first, text_.data() + pos_, out.number);
    if (ec == std::errc::result_out_of_range) {
      if (tooLarge(text_.substr(start, pos_ - start)))
        return fail("a number beyond the range of a double (about 1.8e308)", start);
      out.number = negative ? -0.0 : 0.0;
    } else if (ec != std::errc() || end != text_.data() + pos_) {
      return fail("an invalid number", start);
    }
    return true;
  }

  // A string starting at its opening quote, its escapes resolved into `out`.
  bool string(std::string& out) {
    const std::size_t start = pos_;
    ++pos_;
    for (;;) {
      // Plain characters in runs: embedded base64 buffers make strings of megabytes.
      const std::size_t run = pos_;
      while (pos_ < text_.size()) {
        const auto c = static_cast<unsigned char>(text_[pos_]);
        if (c == '"' || c == '\\' || c < 0x20 || c >= 0x80)
          break;
        ++pos_;
      }
      out.append(text_.substr(run, pos_ - run));
      if (pos_ >= text_.size())
        return fail("an unterminated string", start);
      const auto c = static_cast<unsigned char>(text_[pos_]);
      if (c == '"') {
        ++pos_;
        return true;
      }
      if (c < 0x20)
        return fail("a control character (" + shown(char(c)) +
                    ") in a string, where JSON needs an escape");
      if (c >= 0x80) {
        const std::size_t at = pos_;
        if (!utf8Sequence())
          return fail("invalid UTF-8 in a string", at);
        out.append(text_.substr(at, pos_ - at));
        continue;
      }
      if (!escape(out, start))
        return false;
    }
  }

  // One multi-byte UTF-8 character at pos_ (Unicode's well-formed sequences: no overlong
  // form, no surrogate, nothing past U+10FFFF), stepped over.
  bool utf8Sequence() {
    const auto byte = [&](std::size_t at) {
      return at < text_.size() ? static_cast<unsigned char>(text_[at]) : 0u;
    };
    const unsigned lead = byte(pos_);
    unsigned length = 0, low = 0x80, high = 0xBF;  // the second byte's range
    if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      low = lead == 0xE0 ? 0xA0 : 0x80;
      high = lead == 0xED ? 0x9F : 0xBF;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      low = lead == 0xF0 ? 0x90 : 0x80;
      high = lead == 0xF4 ? 0x8F : 0xBF;
    } else {
      return false;
    }
    if (byte(pos_ + 1) < low || byte(pos_ + 1) > high)
      return false;
    for (unsigned k = 2; k < length; ++k) {
      if (byte(pos_ + k) < 0x80 || byte(pos_ + k) > 0xBF)
        return false;
    }
    pos_ += length;
    return true;
  }

  // Four hexadecimal digits at `at`.
  bool hex4(std::size_t at, std::uint32_t& code) const {
    if (text_.size() < 4 || at > text_.size() - 4)
      return false;
    code = 0;
    for (std::size_t k = at; k < at + 4; ++k) {
      const char c = text_[k];
      const int d = c >= '0' && c <= '9'   ? c - '0'
                    : c >= 'a' && c <= 'f' ? c - 'a' + 10
                    : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                           : -1;
      if (d < 0)
        return false;
      code = code << 4 | std::uint32_t(d);
    }
    return true;
  }

  // An escape at pos_ (its backslash) in the string opened at `start`.
  bool escape(std::string& out, std::size_t start) {
    const std::size_t at = pos_;
    if (pos_ + 1 >= text_.size())
      return fail("an unterminated string", start);
    const char e = text_[pos_ + 1];
    pos_ += 2;
    switch (e) {
      case '"':
      case '\\':
      case '/':
        out += e;
        return true;
      case 'b':
        out += '\b';
        return true;
      case 'f':
        out += '\f';
        return true;
      case 'n':
        out += '\n';
        return true;
      case 'r':
        out += '\r';
        return true;
      case 't':
        out += '\t';
        return true;
      case 'u':
        break;
      default:
        return fail(e > ' ' && e < 0x7F
                        ? std::string("an invalid escape '\\") + e + "' in a string"
                        : "an invalid escape in a string (a backslash, then " + shown(e) + ")",
                    at);
    }
    std::uint32_t code = 0;
    if (!hex4(pos_, code))
      return fail("an invalid \\u escape (it takes four hexadecimal digits)", at);
    pos_ += 4;
    if (code >= 0xDC00 && code < 0xE000)
      return fail("an unpaired surrogate in a \\u escape", at);
    if (code >= 0xD800 && code < 0xDC00) {  // the high half of a pair: the low half follows
      std::uint32_t low = 0;
      if (text_.substr(pos_, 2) != "\\u" || !hex4(pos_ + 2, low) || low < 0xDC00 || low >= 0xE000)
        return fail("an unpaired surrogate in a \\u escape", at);
      pos_ += 6;
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    appendUtf8(out, code);
    return true;
  }

  std::string_view text_;
  int maxDepth_;
  std::size_t maxValues_;
  std::size_t values_ = 0;
  std::size_t pos_ = 0;
  JsonError error_;
};

}  // namespace

std::optional<JsonValue> readJson(std::string_view text, JsonError& error, int maxDepth,
                                  std::size_t maxValues) {
  return Reader(text, maxDepth, maxValues).read(error);
}

}  // namespace memograph::io
