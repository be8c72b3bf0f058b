#include "tools/io/gltf_precheck.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/input_file.h"
#include "tools/io/json_reader.h"

namespace memograph::io {
namespace {

std::uint32_t readU32(const std::string& bytes, std::size_t at) {
  return std::uint32_t(std::uint8_t(bytes[at])) | std::uint32_t(std::uint8_t(bytes[at + 1])) << 8 |
         std::uint32_t(std::uint8_t(bytes[at + 2])) << 16 |
         std::uint32_t(std::uint8_t(bytes[at + 3])) << 24;
}

class Checker {
 public:
  Checker(const JsonValue& root, const std::string& path, std::string_view binChunk,
          compiler::Diagnostics& diagnostics)
      : root_(root), path_(path), binChunk_(binChunk), diagnostics_(diagnostics) {}

  bool run() {
    const JsonValue& nodes = array("nodes");
    checkHierarchy(nodes);
    for (std::size_t s = 0; s < array("scenes").size(); ++s) {
      if (const JsonValue* list = array("scenes").items[s].get("nodes")) {
        for (const JsonValue& n : list->items)
          index(n, "nodes", "scenes[" + std::to_string(s) + "].nodes");
      }
    }
    if (const JsonValue* scene = root_.get("scene"))
      index(*scene, "scenes", "scene");
    for (std::size_t a = 0; a < array("accessors").size(); ++a)
      checkAccessor(array("accessors").items[a], "accessors[" + std::to_string(a) + "]");
    for (std::size_t v = 0; v < array("bufferViews").size(); ++v)
      checkView(array("bufferViews").items[v], "bufferViews[" + std::to_string(v) + "]");
    for (std::size_t b = 0; b < array("buffers").size(); ++b) {
      checkExternalBuffer(b);
      checkDataUri(array("buffers").items[b], "buffers[" + std::to_string(b) + "].uri");
    }
    for (std::size_t i = 0; i < array("images").size(); ++i)
      checkDataUri(array("images").items[i], "images[" + std::to_string(i) + "].uri");
    // Index values are read only once every range above is known to be good.
    const bool rangesGood = ok_;
    for (std::size_t m = 0; m < array("meshes").size(); ++m)
      checkMesh(array("meshes").items[m], "meshes[" + std::to_string(m) + "]", rangesGood);
    for (std::size_t t = 0; t < array("textures").size(); ++t) {
      const JsonValue& texture = array("textures").items[t];
      const std::string where = "textures[" + std::to_string(t) + "]";
      if (const JsonValue* source = texture.get("source"))
        index(*source, "images", where + ".source");
      if (const JsonValue* sampler = texture.get("sampler"))
        index(*sampler, "samplers", where + ".sampler");
    }
    for (std::size_t i = 0; i < array("images").size(); ++i) {
      if (const JsonValue* view = array("images").items[i].get("bufferView"))
        index(*view, "bufferViews", "images[" + std::to_string(i) + "].bufferView");
    }
    for (std::size_t m = 0; m < array("materials").size(); ++m)
      checkTextureReferences(array("materials").items[m], "materials[" + std::to_string(m) + "]",
                             0);
    return ok_;
  }

 private:
  const JsonValue& array(const char* name) {
    static const JsonValue empty;
    const JsonValue* value = root_.get(name);
    return value && value->kind == JsonValue::Kind::Array ? *value : empty;
  }
  void error(const std::string& message) {
    if (errors_++ < 10)  // enough to fix the file; a generated one may have millions
      diagnostics_.error(path_, message);
    ok_ = false;
  }
  // An index into the top-level array `into`: a whole number in range.
  bool index(const JsonValue& value, const char* into, const std::string& where) {
    const std::size_t count = array(into).size();
    if (value.kind != JsonValue::Kind::Number || value.number < 0 ||
        value.number != std::floor(value.number) || value.number >= double(count)) {
      error(where + " is " +
            (value.kind == JsonValue::Kind::Number ? format(value.number) : "not a number") +
            ", out of range: the file has " + std::to_string(count) + " " + into);
      return false;
    }
    return true;
  }
  static std::string format(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
  }
  // A whole number in [lo, hi]: byte offsets, lengths, strides and counts (2^53 bounds
  // what a double holds exactly, and keeps every cast to an integer defined).
  static bool whole(double v, double lo = 0.0, double hi = 9007199254740992.0) {
    return v >= lo && v <= hi && v == std::floor(v);
  }
  static double numberOr(const JsonValue* value, double fallback) {
    return value && value->kind == JsonValue::Kind::Number ? value->number : fallback;
  }

  // Whether a node's own transform collapses space (zero scale, a zero quaternion, a
  // singular or non-finite matrix): a camera under it sees nothing.
  static bool degenerate(const JsonValue& node) {
    if (const JsonValue* scale = node.get("scale"); scale && scale->size() == 3) {
      for (const JsonValue& s : scale->items) {
        if (s.kind != JsonValue::Kind::Number || !std::isfinite(s.number) ||
            std::abs(s.number) < 1e-12)
          return true;
      }
    }
    if (const JsonValue* rotation = node.get("rotation"); rotation && rotation->size() == 4) {
      double norm = 0.0;
      for (const JsonValue& r : rotation->items)
        norm += r.number * r.number;
      if (!(norm > 1e-12) || !std::isfinite(norm))
        return true;
    }
    if (const JsonValue* matrix = node.get("matrix"); matrix && matrix->size() == 16) {
      double m[16];
      for (int i = 0; i < 16; ++i) {
        m[i] = matrix->items[i].number;
        if (!std::isfinite(m[i]))
          return true;
      }
      // Column-major: the upper 3x3 is m[0..2], m[4..6], m[8..10].
      const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) +
                         m[8] * (m[1] * m[6] - m[2] * m[5]);
      if (!(std::abs(det) > 1e-18))
        return true;
    }
    return false;
  }

  // Without recursion: parents first, then the depth of each node by walking up.
  void checkHierarchy(const JsonValue& nodes) {
    const std::size_t n = nodes.size();
    std::vector<std::int64_t> parent(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      const JsonValue& node = nodes.items[i];
      const std::string where = "nodes[" + std::to_string(i) + "]";
      if (const JsonValue* mesh = node.get("mesh"))
        index(*mesh, "meshes", where + ".mesh");
      if (const JsonValue* camera = node.get("camera"))
        index(*camera, "cameras", where + ".camera");
      if (const JsonValue* skin = node.get("skin"))
        index(*skin, "skins", where + ".skin");
      const JsonValue* children = node.get("children");
      if (!children)
        continue;
      for (const JsonValue& child : children->items) {
        if (!index(child, "nodes", where + ".children"))
          continue;
        const auto c = static_cast<std::size_t>(child.number);
        if (parent[c] != -1 || c == i) {
          error("nodes[" + std::to_string(c) +
                "] has more than one parent (or is its own "
                "child); a glTF node hierarchy is a tree");
          continue;
        }
        parent[c] = std::int64_t(i);
      }
    }
    if (!ok_)
      return;
    // Depths by walking up from each node, memoised; a walk longer than n is a cycle.
    std::vector<int> depth(n, 0);  // 0: not known yet
    std::vector<std::size_t> chain;
    for (std::size_t i = 0; i < n; ++i) {
      chain.clear();
      std::size_t at = i;
      while (depth[at] == 0 && parent[at] != -1 && chain.size() <= n) {
        chain.push_back(at);
        at = std::size_t(parent[at]);
      }
      if (chain.size() > n) {
        error("the node hierarchy has a cycle through nodes[" + std::to_string(i) + "]");
        return;
      }
      int d = depth[at] == 0 ? 1 : depth[at];
      depth[at] = d;
      for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        depth[*it] = ++d;
      if (d > kMaxNodeDepth) {
        error("the node hierarchy is " + std::to_string(d) + " levels deep at nodes[" +
              std::to_string(i) + "], over the limit of " + std::to_string(kMaxNodeDepth) +
              " (docs/guide/limits.md)");
        return;
      }
    }
    // A camera whose node or an ancestor collapses space renders an all-black image.
    for (std::size_t i = 0; i < n; ++i) {
      if (!nodes.items[i].get("camera"))
        continue;
      for (std::int64_t at = std::int64_t(i); at != -1; at = parent[std::size_t(at)]) {
        if (degenerate(nodes.items[std::size_t(at)])) {
          error("the camera of nodes[" + std::to_string(i) + "] is under a degenerate transform " +
                "(zero scale, zero rotation or a singular matrix) at nodes[" + std::to_string(at) +
                "]: it would see nothing");
          break;
        }
      }
    }
  }

  void checkMesh(const JsonValue& mesh, const std::string& where, bool readIndices) {
    const JsonValue* primitives = mesh.get("primitives");
    if (!primitives)
      return;
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const JsonValue& primitive = primitives->items[p];
      const std::string at = where + ".primitives[" + std::to_string(p) + "]";
      if (const JsonValue* attributes = primitive.get("attributes")) {
        for (const JsonMember& attribute : attributes->members)
          index(attribute.value, "accessors", at + ".attributes." + attribute.key);
      }
      if (const JsonValue* indices = primitive.get("indices"))
        index(*indices, "accessors", at + ".indices");
      if (const JsonValue* material = primitive.get("material"))
        index(*material, "materials", at + ".material");
      if (readIndices && ok_)
        checkIndexValues(primitive, at);
    }
  }

  // assimp drops a triangle with a vertex index past the vertex count without a word (an
  // incomplete mesh, exit 0): the index values are read here and checked.
  void checkIndexValues(const JsonValue& primitive, const std::string& at) {
    const JsonValue* indices = primitive.get("indices");
    const JsonValue* attributes = primitive.get("attributes");
    const JsonValue* position = attributes ? attributes->get("POSITION") : nullptr;
    if (!indices || !position)
      return;
    const JsonValue& accessor = array("accessors").items[std::size_t(indices->number)];
    const double vertices =
        numberOr(array("accessors").items[std::size_t(position->number)].get("count"), 0);
    const JsonValue* viewIndex = accessor.get("bufferView");
    if (!viewIndex)
      return;
    const JsonValue& view = array("bufferViews").items[std::size_t(viewIndex->number)];
    const std::string* buffer = bufferBytes(std::size_t(numberOr(view.get("buffer"), 0)));
    if (!buffer)
      return;
    const std::uint64_t size = componentBytes(numberOr(accessor.get("componentType"), 0));
    const double countValue = numberOr(accessor.get("count"), 0);
    const double strideValue = numberOr(view.get("byteStride"), double(size));
    const double startValue =
        numberOr(view.get("byteOffset"), 0) + numberOr(accessor.get("byteOffset"), 0);
    // Checked above already; again here so that no cast below can be undefined.
    if (size == 0 || !whole(countValue) || !whole(strideValue, 1) || !whole(startValue))
      return;
    const auto count = std::uint64_t(countValue);
    const auto stride = std::max(std::uint64_t(strideValue), size);
    const auto start = std::uint64_t(startValue);
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::uint64_t at8 = start + i * stride;
      if (at8 + size > buffer->size())
        return;  // the buffer is shorter than declared: assimp reports it
      std::uint64_t value = 0;
      for (std::uint64_t b = 0; b < size; ++b)
        value |= std::uint64_t(std::uint8_t((*buffer)[at8 + b])) << (8 * b);
      if (double(value) >= vertices) {
        error(at + ".indices: index " + std::to_string(i) + " is " + std::to_string(value) +
              ", out of range: the primitive has " + format(vertices) + " vertices");
        return;
      }
    }
  }

  // A buffer in a file beside the glTF (a `uri` that is not `data:`), as assimp opens it:
  // the glTF's folder joined with the URI as written (assimp decodes no %-escapes). It must
  // be a regular file within the scene limit holding the buffer's byteLength; an absolute
  // path is refused (assimp would read it only for a glTF named without a folder). assimp
  // opens no file for a buffer of byteLength 0, and neither does this.
  void checkExternalBuffer(std::size_t b) {
    const JsonValue& buffer = array("buffers").items[b];
    const JsonValue* uri = buffer.get("uri");
    if (!uri || uri->kind != JsonValue::Kind::String || uri->string.rfind("data:", 0) == 0)
      return;
    const double length = numberOr(buffer.get("byteLength"), 0);
    if (!(length > 0))
      return;
    const std::string shown =
        uri->string.size() > 200 ? uri->string.substr(0, 200) + "..." : uri->string;
    const std::string where = "buffers[" + std::to_string(b) + "].uri '" + shown + "'";
    const std::string& name = uri->string;
    if (name.empty() || name.find('\0') != std::string::npos) {
      error(where + " is not a file name");
      return;
    }
    if (name[0] == '/' || name[0] == '\\') {
      error(where + " is an absolute path; a buffer's URI is relative to the glTF file");
      return;
    }
    const std::filesystem::path file = externalPath(name);
    std::string fileError;
    const auto size = files::checkInputFile(file, files::kMaxSceneFileBytes, "scenes", fileError);
    if (!size) {
      error(where + ": " + file.string() + ": " + fileError);
      return;
    }
    if (double(*size) < length) {
      error(where + ": " + file.string() + " has " + std::to_string(*size) +
            " bytes, fewer than the buffer's byteLength of " + format(length));
    }
  }
  std::filesystem::path externalPath(const std::string& name) const {
    return std::filesystem::path(path_).parent_path() / name;
  }

  // A data: URI split as assimp 5.2 splits it (glTFCommon ParseDataURI): the header up to
  // the first ',' (a media type, then ';'-separated parameters, base64 when one starts with
  // "base64"), the payload after it.
  struct DataUri {
    std::string_view header, payload;
    bool base64 = false;
  };
  static DataUri splitDataUri(std::string_view text) {
    DataUri out;
    const std::size_t comma = text.find(',');
    out.header = text.substr(5, comma == std::string_view::npos ? text.npos : comma - 5);
    out.payload = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    for (std::size_t at = out.header.find(';'); at != std::string_view::npos;
         at = out.header.find(';', at + 1)) {
      if (out.header.substr(at + 1, 6) == "base64")
        out.base64 = true;
    }
    return out;
  }

  // assimp 5.2 keeps the payload's offset in a char (a header over 127 characters wraps it
  // and reads before the string), allocates a base64 payload's decoded size and then throws
  // on a byte over 127 without freeing it, and decodes other characters outside the
  // alphabet as zeros (found by memograph_gltf_import_fuzzer: a leak). So a data: URI has a
  // short header, and base64 data is whole groups of four characters of the alphabet with
  // '=' padding only at the end.
  void checkDataUri(const JsonValue& owner, const std::string& where) {
    const JsonValue* uri = owner.get("uri");
    if (!uri || uri->kind != JsonValue::Kind::String || uri->string.rfind("data:", 0) != 0)
      return;
    const DataUri data = splitDataUri(uri->string);
    if (data.header.size() > 100) {
      error(where + ": the data: URI's media type and parameters are " +
            std::to_string(data.header.size()) + " characters, over 100");
      return;
    }
    if (!data.base64)
      return;
    const std::string_view payload = data.payload;
    for (std::size_t i = 0; i < payload.size(); ++i) {
      const char c = payload[i];
      const bool alphabet = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                            (c >= '0' && c <= '9') || c == '+' || c == '/';
      const bool padding =
          c == '=' && i + 2 >= payload.size() && (i + 1 == payload.size() || payload[i + 1] == '=');
      if (!alphabet && !padding) {
        char shown[8];
        std::snprintf(shown, sizeof shown, "0x%02x", unsigned(std::uint8_t(c)));
        error(where + ": the base64 data has a character that is not base64 (" + shown +
              " at character " + std::to_string(i) + ")");
        return;
      }
    }
    if (payload.size() % 4 != 0) {
      error(where + ": the base64 data is " + std::to_string(payload.size()) +
            " characters, not a whole number of 4-character groups");
    }
  }

  // A buffer's bytes: the .glb BIN chunk, a base64 data: URI, or the file beside the glTF
  // (checkExternalBuffer found it readable); empty when it cannot be read here.
  const std::string* bufferBytes(std::size_t b) {
    if (b >= array("buffers").size())
      return nullptr;
    if (decoded_.size() < array("buffers").size())
      decoded_.resize(array("buffers").size());
    auto& slot = decoded_[b];
    if (slot.first)
      return &slot.second;  // empty when not readable here: nothing is checked
    slot.first = true;
    const JsonValue* uri = array("buffers").items[b].get("uri");
    if (!uri) {
      slot.second.assign(binChunk_);
      return &slot.second;
    }
    const std::string& text = uri->string;
    if (text.rfind("data:", 0) != 0) {
      std::string ignored;  // reported by checkExternalBuffer
      if (auto bytes = files::readInputFile(externalPath(text), files::kMaxSceneFileBytes, "scenes",
                                            ignored))
        slot.second = std::move(*bytes);
      return &slot.second;
    }
    const DataUri data = splitDataUri(text);
    slot.second = data.base64 ? base64(data.payload) : std::string(data.payload);
    return &slot.second;
  }

  static std::string base64(std::string_view text) {
    std::string out;
    out.reserve(text.size() / 4 * 3);
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
      int v;
      if (c >= 'A' && c <= 'Z')
        v = c - 'A';
      else if (c >= 'a' && c <= 'z')
        v = c - 'a' + 26;
      else if (c >= '0' && c <= '9')
        v = c - '0' + 52;
      else if (c == '+' || c == '-')
        v = 62;
      else if (c == '/' || c == '_')
        v = 63;
      else
        continue;  // padding, whitespace
      bits = (bits << 6) | std::uint32_t(v);
      if (++count == 4) {
        out.push_back(char(bits >> 16));
        out.push_back(char(bits >> 8));
        out.push_back(char(bits));
        bits = 0;
        count = 0;
      }
    }
    if (count == 3) {
      out.push_back(char(bits >> 10));
      out.push_back(char(bits >> 2));
    } else if (count == 2) {
      out.push_back(char(bits >> 4));
    }
    return out;
  }

  static std::uint64_t componentBytes(double type) {
    // Range first: converting a double beyond int's range is undefined (found by
    // memograph_gltf_import_fuzzer: "componentType": 5.2e92).
    if (!(type >= 0 && type <= 65535))
      return 0;
    switch (static_cast<int>(type)) {
      case 5120:
      case 5121:
        return 1;
      case 5122:
      case 5123:
        return 2;
      case 5125:
      case 5126:
        return 4;
      default:
        return 0;
    }
  }
  static std::uint64_t components(const std::string& type) {
    if (type == "SCALAR")
      return 1;
    if (type == "VEC2")
      return 2;
    if (type == "VEC3")
      return 3;
    if (type == "VEC4" || type == "MAT2")
      return 4;
    if (type == "MAT3")
      return 9;
    if (type == "MAT4")
      return 16;
    return 0;
  }

  void checkAccessor(const JsonValue& accessor, const std::string& where) {
    const double count = numberOr(accessor.get("count"), -1);
    const std::uint64_t bytes = componentBytes(numberOr(accessor.get("componentType"), 0));
    const JsonValue* type = accessor.get("type");
    const std::uint64_t n = type ? components(type->string) : 0;
    if (count < 0 || count != std::floor(count) || bytes == 0 || n == 0) {
      error(where + " needs a whole count >= 0, a known componentType and type");
      return;
    }
    const JsonValue* view = accessor.get("bufferView");
    if (!view)
      return;  // all zeros (or sparse): nothing to read out of range
    if (!index(*view, "bufferViews", where + ".bufferView"))
      return;
    const JsonValue& bufferView = array("bufferViews").items[std::size_t(view->number)];
    const std::uint64_t element = bytes * n;
    const double stride = numberOr(bufferView.get("byteStride"), double(element));
    const double offset = numberOr(accessor.get("byteOffset"), 0);
    const double length = numberOr(bufferView.get("byteLength"), 0);
    const double end = count == 0 ? offset : offset + (count - 1) * stride + double(element);
    if (!whole(offset) || !whole(stride) || !whole(count) || end > length) {
      error(where + " reads bytes " + format(offset) + " to " + format(end) +
            " of a buffer view of " + format(length) + " bytes: out of range");
    }
  }

  void checkView(const JsonValue& view, const std::string& where) {
    const JsonValue* buffer = view.get("buffer");
    if (!buffer || !index(*buffer, "buffers", where + ".buffer"))
      return;
    const double offset = numberOr(view.get("byteOffset"), 0);
    const double length = numberOr(view.get("byteLength"), -1);
    // The glTF specification's range for a stride; 0 would make readers loop in place.
    if (const JsonValue* stride = view.get("byteStride");
        stride && !whole(numberOr(stride, -1), 4, 252)) {
      error(where + ".byteStride must be a whole number from 4 to 252");
      return;
    }
    const double bufferLength =
        numberOr(array("buffers").items[std::size_t(buffer->number)].get("byteLength"), 0);
    if (!whole(offset) || !whole(length) || offset + length > bufferLength) {
      error(where + " covers bytes " + format(offset) + " to " + format(offset + length) +
            " of a buffer of " + format(bufferLength) + " bytes: out of range");
    }
  }

  // Texture references ({"index": i} under a member named *Texture) anywhere in a material.
  void checkTextureReferences(const JsonValue& value, const std::string& where, int depth) {
    if (depth > kMaxJsonDepth)
      return;
    for (const auto& [name, member] : value.members) {
      if (member.kind != JsonValue::Kind::Object)
        continue;
      if (name.size() >= 7 && name.compare(name.size() - 7, 7, "Texture") == 0) {
        if (const JsonValue* i = member.get("index"))
          index(*i, "textures", where + "." + name + ".index");
      }
      checkTextureReferences(member, where + "." + name, depth + 1);
    }
  }

  const JsonValue& root_;
  const std::string& path_;
  std::string_view binChunk_;
  compiler::Diagnostics& diagnostics_;
  std::vector<std::pair<bool, std::string>> decoded_;  // (tried, bytes) per buffer
  bool ok_ = true;
  int errors_ = 0;
};

}  // namespace

bool precheckGltfBytes(const std::string& path, const std::string& bytes, bool glb,
                       compiler::Diagnostics& diagnostics) {
  std::string_view json = bytes;
  std::string_view binChunk;
  if (glb) {
    // 12-byte header (magic, version, length), then chunks of (length, type, data).
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) {
      diagnostics.error(path, "not a binary glTF file (no 'glTF' header)");
      return false;
    }
    const std::uint32_t version = readU32(bytes, 4);
    const std::uint32_t length = readU32(bytes, 8);
    if (version != 2) {
      diagnostics.error(
          path, "binary glTF version " + std::to_string(version) + "; only version 2 is read");
      return false;
    }
    if (length > bytes.size()) {
      diagnostics.error(path, "the .glb header declares " + std::to_string(length) +
                                  " bytes, but the file has " + std::to_string(bytes.size()));
      return false;
    }
    const std::uint32_t jsonLength = readU32(bytes, 12);
    if (readU32(bytes, 16) != 0x4E4F534Au) {  // "JSON"
      diagnostics.error(path, "the first .glb chunk is not JSON");
      return false;
    }
    if (std::uint64_t(jsonLength) + 20 > length) {
      diagnostics.error(path, "the .glb JSON chunk declares " + std::to_string(jsonLength) +
                                  " bytes, more than the " + std::to_string(length) +
                                  "-byte file holds");
      return false;
    }
    std::uint64_t at = 20 + std::uint64_t(jsonLength);
    at = (at + 3) & ~std::uint64_t(3);
    while (at + 8 <= length) {  // further chunks (BIN): each within the file
      const std::uint64_t chunk = readU32(bytes, at);
      if (at + 8 + chunk <= length && readU32(bytes, at + 4) == 0x004E4942u && binChunk.empty())
        binChunk = std::string_view(bytes).substr(at + 8, chunk);  // "BIN"
      if (at + 8 + chunk > length) {
        diagnostics.error(path, "a .glb chunk at byte " + std::to_string(at) + " declares " +
                                    std::to_string(chunk) + " bytes, more than the file holds");
        return false;
      }
      at = (at + 8 + chunk + 3) & ~std::uint64_t(3);
    }
    json = std::string_view(bytes).substr(20, jsonLength);
  }
  // The tree keeps every string, at most the JSON's size again: a large .gltf is mostly its
  // data: URIs, which the index check decodes anyway.
  JsonError error;
  const std::optional<JsonValue> root = readJson(json, error, kMaxJsonDepth);
  if (!root) {
    diagnostics.error(path, "invalid glTF JSON: " + error.message + " (at byte " +
                                std::to_string(error.offset) + " of the JSON)");
    return false;
  }
  if (root->kind != JsonValue::Kind::Object) {
    diagnostics.error(path, "invalid glTF: the JSON is not an object");
    return false;
  }
  return Checker(*root, path, binChunk, diagnostics).run();
}

bool precheckGltf(const std::string& path, compiler::Diagnostics& diagnostics) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".gltf" && ext != ".glb")
    return true;
  std::string error;
  // A .glb is read whole (its size is bounded by the scene limit); assimp reads it again.
  auto bytes = files::readInputFile(path, files::kMaxSceneFileBytes, "scenes", error);
  if (!bytes) {
    diagnostics.error(path, error);
    return false;
  }
  return precheckGltfBytes(path, *bytes, ext == ".glb", diagnostics);
}

}  // namespace memograph::io
