#include "tools/io/obj_precheck.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>

#include "compiler/input_file.h"
#include "runtime/scene/scene_limits.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back()))
    s.remove_suffix(1);
  return s;
}

// One line of an OBJ or MTL file: its first word and where the rest starts.
struct Line {
  std::string_view keyword;
  std::string_view rest;     // trimmed
  std::uint32_t restColumn;  // 1-based column of `rest`
};

Line splitLine(std::string_view line) {
  std::size_t k = 0;
  while (k < line.size() && isSpace(line[k]))
    ++k;
  const std::size_t start = k;
  while (k < line.size() && !isSpace(line[k]))
    ++k;
  Line out{line.substr(start, k - start), {}, 0};
  while (k < line.size() && isSpace(line[k]))
    ++k;
  out.rest = trim(line.substr(k));
  out.restColumn = static_cast<std::uint32_t>(k + 1);
  return out;
}

// Calls `visit(line, lineNumber)` for each line of `text` ('\n' ends a line, as assimp's
// readers take it; a '\r' before it is trimmed with the rest).
template <typename Visit>
void forEachLine(std::string_view text, Visit&& visit) {
  std::uint32_t number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    ++number;
    if (!visit(text.substr(0, end), number))
      return;
    if (end == std::string_view::npos)
      break;
    text.remove_prefix(end + 1);
  }
}

bool isNumberOrSwitch(std::string_view token) {
  if (token == "on" || token == "off" || token.size() == 1)  // -imfchan r|g|b|m|l|z
    return true;
  return !token.empty() && std::all_of(token.begin(), token.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
           c == 'e' || c == 'E';
  });
}

// A texture statement's file name: what follows its options (`-o 1 1 1 -clamp on name`),
// the rest of the line, as assimp's MTL reader takes it (names may hold spaces).
std::string_view textureName(std::string_view rest, std::uint32_t& column) {
  while (!rest.empty() && rest.front() == '-') {
    std::size_t k = 0;
    auto skipToken = [&] {
      while (k < rest.size() && !isSpace(rest[k]))
        ++k;
      while (k < rest.size() && isSpace(rest[k]))
        ++k;
    };
    skipToken();  // the option
    // Its arguments: numbers, on/off, or a channel letter.
    for (;;) {
      std::size_t end = k;
      while (end < rest.size() && !isSpace(rest[end]))
        ++end;
      const std::string_view token = rest.substr(k, end - k);
      if (token.empty() || end == rest.size() || !isNumberOrSwitch(token))
        break;
      skipToken();
    }
    column += static_cast<std::uint32_t>(k);
    rest.remove_prefix(k);
  }
  return rest;
}

bool isTextureKeyword(std::string_view keyword) {
  std::string lower(keyword);
  for (char& c : lower)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.rfind("map_", 0) == 0 || lower == "bump" || lower == "disp" || lower == "decal" ||
         lower == "refl" || lower == "norm";
}

class ObjChecker {
 public:
  ObjChecker(const std::string& path, compiler::Diagnostics& diagnostics)
      : path_(path), diagnostics_(diagnostics) {}

  bool run(const std::string& bytes) {
    const std::size_t errorsBefore = diagnostics_.errorCount();
    const compiler::SourceFile obj{path_, {}};
    std::string material;
    bool split = true;  // the next face starts a mesh
    std::uint64_t meshes = 0;
    forEachLine(bytes, [&](std::string_view text, std::uint32_t number) {
      const Line line = splitLine(text);
      if (line.keyword == "mtllib") {
        checkLibrary(obj, number, line);
      } else if (line.keyword == "o" || line.keyword == "g") {
        split = true;
      } else if (line.keyword == "usemtl") {
        if (line.rest != material) {
          material = std::string(line.rest);
          split = true;
        }
      } else if (line.keyword == "f" && split) {
        split = false;
        if (++meshes > runtime::kMaxSceneMeshes) {
          diagnostics_.error(obj, {number, 1},
                             "this face starts mesh " + std::to_string(meshes) +
                                 " of the OBJ (a mesh per material switch within each object "
                                 "or group), more than the limit of " +
                                 std::to_string(runtime::kMaxSceneMeshes) +
                                 " meshes a scene may have (each is an acceleration structure "
                                 "of its own)");
          return false;
        }
      }
      return true;
    });
    return diagnostics_.errorCount() == errorsBefore;
  }

 private:
  // An external file named at `where` (`column` of `line` of `file`), resolved against
  // `referrer`'s folder. Returns its size when it is a regular file within the limit;
  // nothing (after an error, or a warning for a missing file) otherwise.
  std::optional<std::uint64_t> checkExternal(const compiler::SourceFile& file,
                                             compiler::SourceLocation where, std::string_view name,
                                             const std::string& what, fs::path& resolved) {
    const std::string shown =
        name.size() > 200 ? std::string(name.substr(0, 200)) + "..." : std::string(name);
    if (name.empty()) {
      diagnostics_.error(file, where, what + " names no file");
      return std::nullopt;
    }
    if (name.find('\0') != std::string_view::npos) {
      diagnostics_.error(file, where, what + " '" + shown + "' is not a file name");
      return std::nullopt;
    }
    if (name.front() == '/' || name.front() == '\\' ||
        (name.size() > 1 && name[1] == ':' && std::isalpha(static_cast<unsigned char>(name[0])))) {
      diagnostics_.error(
          file, where,
          what + " '" + shown + "' is an absolute path; it must be relative to " + file.path);
      return std::nullopt;
    }
    resolved = fs::path(file.path).parent_path() / fs::path(std::string(name));
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(resolved, ec);
    if (status.type() == fs::file_type::not_found) {
      diagnostics_.warning(file, where,
                           what + " '" + shown + "' does not exist (looked for " +
                               resolved.string() + "); the import goes on without it");
      return std::nullopt;
    }
    std::string error;
    const auto size = files::checkInputFile(resolved, files::kMaxSceneFileBytes, "scenes", error);
    if (!size)
      diagnostics_.error(file, where,
                         what + " '" + shown + "': " + resolved.string() + ": " + error);
    return size;
  }

  void checkLibrary(const compiler::SourceFile& obj, std::uint32_t number, const Line& line) {
    fs::path resolved;
    const auto size =
        checkExternal(obj, {number, line.restColumn}, line.rest, "the material library", resolved);
    if (!size) {
      // A missing library makes assimp open <OBJ name without "obj">mtl instead: checked as
      // if named here.
      std::error_code ec;
      if (path_.size() < 3 || fs::symlink_status(resolved, ec).type() != fs::file_type::not_found)
        return;
      const std::string fallback = path_.substr(0, path_.size() - 3) + "mtl";
      if (fs::symlink_status(fallback, ec).type() == fs::file_type::not_found)
        return;
      std::string error;
      if (!files::checkInputFile(fallback, files::kMaxSceneFileBytes, "scenes", error)) {
        diagnostics_.error(obj, {number, line.restColumn},
                           "the fallback material library " + fallback + " (read in place of '" +
                               std::string(line.rest) + "'): " + error);
        return;
      }
      resolved = fallback;
    }
    // Each library is read once, however often it is named.
    if (!seen_.insert(resolved.lexically_normal().string()).second)
      return;
    std::string error;
    const auto bytes = files::readInputFile(resolved, files::kMaxSceneFileBytes, "scenes", error);
    if (!bytes) {
      diagnostics_.error(obj, {number, line.restColumn}, resolved.string() + ": " + error);
      return;
    }
    const compiler::SourceFile mtl{resolved.string(), {}};
    bool inMaterial = false;
    forEachLine(*bytes, [&](std::string_view text, std::uint32_t mtlLine) {
      const Line statement = splitLine(text);
      if (statement.keyword == "newmtl")
        inMaterial = true;
      if (!isTextureKeyword(statement.keyword))
        return true;
      // assimp 5.2's MTL reader gives a texture to the current material without checking
      // that there is one: before the first `newmtl` it crashes (found by the OBJ fuzzer).
      if (!inMaterial) {
        diagnostics_.error(mtl, {mtlLine, 1},
                           std::string("'")
                               .append(statement.keyword)
                               .append("' comes before any 'newmtl': a texture belongs to a "
                                       "material"));
        return true;
      }
      std::uint32_t column = statement.restColumn;
      const std::string_view name = textureName(statement.rest, column);
      fs::path texture;
      checkExternal(mtl, {mtlLine, column}, name,
                    "the texture of '" + std::string(statement.keyword) + "'", texture);
      return true;
    });
  }

  const std::string& path_;
  compiler::Diagnostics& diagnostics_;
  std::set<std::string> seen_;
};

}  // namespace

bool precheckObjBytes(const std::string& path, const std::string& bytes,
                      compiler::Diagnostics& diagnostics) {
  return ObjChecker(path, diagnostics).run(bytes);
}

bool precheckObj(const std::string& path, compiler::Diagnostics& diagnostics) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj")
    return true;
  std::string error;
  // Read whole (bounded by the scene limit); assimp reads it again.
  const auto bytes = files::readInputFile(path, files::kMaxSceneFileBytes, "scenes", error);
  if (!bytes) {
    diagnostics.error(path, error);
    return false;
  }
  return precheckObjBytes(path, *bytes, diagnostics);
}

}  // namespace memograph::io
