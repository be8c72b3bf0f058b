// The scene pack's byte codec: little-endian fixed-width values, length-prefixed strings and
// arrays (docs/design/scene-pack.md). The reader checks every read against the bytes left and
// throws PackFormatError with the offset, so the decoder needs no checks of its own.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

namespace memograph::runtime::pack {

static_assert(std::endian::native == std::endian::little,
              "the scene pack is little-endian and written by memcpy");

// FNV-1a, 64 bits: the payload's checksum (catches corruption, not tampering).
inline std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ull;
  }
  return hash;
}

class ByteWriter {
 public:
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void u8(bool v) { value(std::uint8_t(v ? 1 : 0)); }
  // A count: refuses what does not fit the format's 32 bits.
  void count(std::size_t n) {
    if (n > UINT32_MAX)
      throw std::invalid_argument("scene pack: more than 2^32-1 elements in one array");
    value(std::uint32_t(n));
  }
  void string(std::string_view s) {
    count(s.size());
    bytes_.append(s);
  }
  template <typename T>
  void array(const std::vector<T>& items) {
    static_assert(std::is_trivially_copyable_v<T>);
    count(items.size());
    bytes_.append(reinterpret_cast<const char*>(items.data()), items.size() * sizeof(T));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

// A problem at a byte offset of the pack (decodeScenePack turns it into the message).
struct PackFormatError : std::runtime_error {
  PackFormatError(std::size_t at, const std::string& what) : std::runtime_error(what), offset(at) {}
  std::size_t offset;
};

class ByteReader {
 public:
  // `base`: the offset of `bytes` in the file, for the messages.
  ByteReader(std::string_view bytes, std::size_t base) : bytes_(bytes), base_(base) {}

  std::size_t offset() const { return base_ + at_; }
  bool atEnd() const { return at_ == bytes_.size(); }

  template <typename T>
  T value(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::uint32_t u32(const char* what) { return value<std::uint32_t>(what); }
  float f32(const char* what) { return value<float>(what); }
  bool u8(const char* what) {
    const std::size_t at = offset();
    const auto v = value<std::uint8_t>(what);
    if (v > 1)
      throw PackFormatError(at, std::string(what) + " is " + std::to_string(v) + ", not 0 or 1");
    return v == 1;
  }
  glm::vec3 vec3(const char* what) { return value<glm::vec3>(what); }
  std::string string(const char* what) {
    const std::uint32_t n = u32(what);
    need(n, what);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  // An array of `count` elements (its count read first): the bytes are checked to be there
  // before anything is allocated, so a corrupt count cannot ask for gigabytes.
  template <typename T>
  std::vector<T> array(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::uint32_t n = u32(what);
    need(std::uint64_t(n) * sizeof(T), what);
    std::vector<T> items(n);
    std::memcpy(items.data(), bytes_.data() + at_, std::size_t(n) * sizeof(T));
    at_ += std::size_t(n) * sizeof(T);
    return items;
  }
  // A count of records, each at least `minRecordBytes` long, checked against the bytes left.
  std::uint32_t count(const char* what, std::size_t minRecordBytes) {
    const std::size_t at = offset();
    const std::uint32_t n = u32(what);
    if (std::uint64_t(n) * minRecordBytes > bytes_.size() - at_)
      throw PackFormatError(
          at, std::string(what) + " count " + std::to_string(n) + " runs past the end of the file");
    return n;
  }

 private:
  void need(std::uint64_t n, const char* what) const {
    if (n > bytes_.size() - at_)
      throw PackFormatError(offset(), std::string("truncated: ") + what + " needs " +
                                          std::to_string(n) + " bytes, " +
                                          std::to_string(bytes_.size() - at_) + " left");
  }
  std::string_view bytes_;
  std::size_t base_;
  std::size_t at_ = 0;
};

}  // namespace memograph::runtime::pack
