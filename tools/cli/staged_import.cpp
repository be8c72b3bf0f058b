#include "tools/cli/staged_import.h"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <map>
#include <set>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/parser.h"
#include "compiler/source_file.h"
#include "runtime/host/atomic_file.h"

namespace memograph::cli {

namespace {

namespace fs = std::filesystem;

// One entry of index.json: Blender's material name -> its graph file and mgraph name.
struct IndexEntry {
  std::string file, material;
};

// Reads index.json in the one shape the exporter writes (exporter.py, export_materials):
// {"materials": {"<Blender name>": {"file": "<X>.mgraph", "material": "<X>"}, ...}}, any
// whitespace and key order. The schema is two levels of objects of strings, so it is read
// directly instead of through a general JSON value tree; anything else is an error with
// its byte offset.
class IndexReader {
 public:
  explicit IndexReader(std::string_view text) : text_(text) {}

  bool read(std::vector<IndexEntry>& entries, std::string& error) {
    bool sawMaterials = false;
    const bool ok = object([&](const std::string& key) {
      if (key != "materials")
        return fail("unknown key \"" + key + "\" (only \"materials\")");
      if (sawMaterials)
        return fail("\"materials\" given twice");
      sawMaterials = true;
      return materials(entries);
    });
    if (ok && !sawMaterials)
      fail("no \"materials\" object");
    skipSpace();
    if (error_.empty() && pos_ != text_.size())
      fail("text after the JSON value");
    if (!error_.empty()) {
      error = error_ + " (at byte " + std::to_string(errorAt_) + ")";
      return false;
    }
    return true;
  }

 private:
  bool materials(std::vector<IndexEntry>& entries) {
    std::set<std::string> names;
    return object([&](const std::string& blenderName) {
      if (!names.insert(blenderName).second)
        return fail("material \"" + blenderName + "\" listed twice");
      IndexEntry entry;
      bool ok = object([&](const std::string& key) {
        std::string* field = key == "file"       ? &entry.file
                             : key == "material" ? &entry.material
                                                 : nullptr;
        if (!field)
          return fail("unknown key \"" + key + "\" (only \"file\" and \"material\")");
        return string(*field);
      });
      if (ok && (entry.file.empty() || entry.material.empty()))
        ok = fail("material \"" + blenderName + "\" lacks \"file\" or \"material\"");
      entries.push_back(std::move(entry));
      return ok;
    });
  }

  // An object whose every value `member(key)` reads.
  template <typename Member>
  bool object(Member&& member) {
    skipSpace();
    if (!take('{'))
      return fail("expected '{'");
    skipSpace();
    if (take('}'))
      return true;
    while (true) {
      skipSpace();
      std::string key;
      if (!string(key))
        return false;
      skipSpace();
      if (!take(':'))
        return fail("expected ':'");
      skipSpace();
      if (!member(key))
        return false;
      skipSpace();
      if (take('}'))
        return true;
      if (!take(','))
        return fail("expected ',' or '}'");
    }
  }

  bool string(std::string& out) {
    if (!take('"'))
      return fail("expected a string");
    out.clear();
    while (pos_ < text_.size()) {
      const char c = text_[pos_++];
      if (c == '"')
        return true;
      if (static_cast<unsigned char>(c) < 0x20)
        return fail("a control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size())
        break;
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          std::uint32_t code = 0;
          if (!hex4(code))
            return false;
          if (code >= 0xD800 && code < 0xDC00) {  // a surrogate pair (json.dumps' default)
            std::uint32_t low = 0;
            if (!take('\\') || !take('u') || !hex4(low) || low < 0xDC00 || low >= 0xE000)
              return fail("an unpaired surrogate in a \\u escape");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          } else if (code >= 0xDC00 && code < 0xE000) {
            return fail("an unpaired surrogate in a \\u escape");
          }
          appendUtf8(out, code);
          break;
        }
        default:
          return fail("an invalid escape in a string");
      }
    }
    return fail("an unterminated string");
  }

  bool hex4(std::uint32_t& code) {
    if (text_.size() - pos_ < 4)
      return fail("a short \\u escape");
    const char* first = text_.data() + pos_;
    const auto [end, ec] = std::from_chars(first, first + 4, code, 16);
    if (ec != std::errc() || end != first + 4)
      return fail("an invalid \\u escape");
    pos_ += 4;
    return true;
  }

  static void appendUtf8(std::string& out, std::uint32_t code) {
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
  bool fail(std::string message) {
    if (error_.empty()) {
      error_ = std::move(message);
      errorAt_ = pos_;
    }
    return false;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::string error_;
  std::size_t errorAt_ = 0;
};

// What a non-regular, non-folder entry is, for the message.
std::string describeSpecial(const fs::path& path, const struct stat& info) {
  if (S_ISLNK(info.st_mode)) {
    std::error_code ec;
    const fs::path to = fs::read_symlink(path, ec);
    return "is a symbolic link" + (ec ? std::string() : " (to " + to.string() + ")") +
           "; the export may hold only regular files and folders";
  }
  const char* kind = S_ISFIFO(info.st_mode)   ? "a FIFO"
                     : S_ISSOCK(info.st_mode) ? "a socket"
                     : S_ISCHR(info.st_mode)  ? "a character device"
                     : S_ISBLK(info.st_mode)  ? "a block device"
                                              : "not a regular file";
  return std::string("is ") + kind + "; the export may hold only regular files and folders";
}

// A graph file named by the index: a plain file name in the export's top folder.
bool plainGraphName(std::string_view name) {
  return name.size() > 7 && name.substr(name.size() - 7) == ".mgraph" &&
         name.find('/') == std::string_view::npos && name.find('\0') == std::string_view::npos &&
         name[0] != '.';
}

}  // namespace

std::optional<std::size_t> parseExportSummary(std::string_view line) {
  constexpr std::string_view kPrefix = "memograph: wrote ";
  if (line.substr(0, kPrefix.size()) != kPrefix)
    return std::nullopt;
  line.remove_prefix(kPrefix.size());
  std::size_t count = 0;
  const auto [end, ec] = std::from_chars(line.data(), line.data() + line.size(), count);
  if (ec != std::errc() || end == line.data())
    return std::nullopt;
  line.remove_prefix(std::size_t(end - line.data()));
  if (line.substr(0, 13) != " material(s) ")
    return std::nullopt;
  return count;
}

std::string validateStagedExport(const fs::path& staging, const fs::path& displayRoot,
                                 const StagedExportExpectation& expected,
                                 const StagedExportLimits& limits) {
  auto shown = [&](const fs::path& relative) {
    return relative.empty() ? displayRoot.string() : (displayRoot / relative).string();
  };
  struct stat info {};
  if (::lstat(staging.c_str(), &info) != 0)
    return files::errnoMessage(displayRoot.string() + ": the staging folder is gone", errno);
  if (!S_ISDIR(info.st_mode))
    return displayRoot.string() + ": the exporter replaced its staging folder with something " +
           "that is not a folder";

  // Every entry first: types, sizes and counts, without following links.
  std::set<std::string> graphs;  // relative paths of every .mgraph, at any depth
  std::map<std::string, std::uint64_t> sizes;
  std::uint64_t total = 0;
  std::size_t entries = 0;
  std::error_code ec;
  fs::recursive_directory_iterator it(staging, fs::directory_options::none, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const fs::path relative = it->path().lexically_relative(staging);
    if (++entries > limits.maxEntries)
      return displayRoot.string() + ": the export holds more than " +
             std::to_string(limits.maxEntries) + " files and folders";
    if (::lstat(it->path().c_str(), &info) != 0)
      return files::errnoMessage(shown(relative) + ": cannot read", errno);
    if (S_ISDIR(info.st_mode)) {
      if (it.depth() + 1 > limits.maxDepth) {
        return shown(relative) + ": folders nested more than " + std::to_string(limits.maxDepth) +
               " deep in the export";
      }
      continue;
    }
    if (!S_ISREG(info.st_mode))
      return shown(relative) + ": " + describeSpecial(it->path(), info);
    const std::uint64_t size = std::uint64_t(info.st_size);
    const bool isGraph = relative.extension() == ".mgraph";
    const bool isText = isGraph || relative == "index.json";
    const std::uint64_t limit = isText ? limits.maxGraphBytes : limits.maxFileBytes;
    if (size > limit) {
      return shown(relative) + ": the file is " + files::formatBytes(size) +
             ", over the limit of " + files::formatBytes(limit) + " for " +
             (isText ? "graphs and index.json" : "exported files");
    }
    total += size;
    if (total > limits.maxTotalBytes)
      return displayRoot.string() + ": the export is over " +
             files::formatBytes(limits.maxTotalBytes) + " in all";
    sizes[relative.string()] = size;
    if (isGraph)
      graphs.insert(relative.string());
  }
  if (ec)
    return shown("") + ": cannot list the export: " + files::describeFileError(ec);

  // The index: present, valid, and naming exactly the graphs present.
  if (!sizes.count("index.json")) {
    return shown("index.json") +
           ": missing: the exporter wrote no index (did Blender run the exporter script?)";
  }
  std::string error;
  const auto indexText =
      files::readInputFile(staging / "index.json", limits.maxGraphBytes, "index.json", error);
  if (!indexText)
    return shown("index.json") + ": " + error;
  std::vector<IndexEntry> index;
  if (!IndexReader(*indexText).read(index, error))
    return shown("index.json") + ": not the exporter's index: " + error;
  std::set<std::string> named;
  for (const auto& entry : index) {
    if (!plainGraphName(entry.file))
      return shown("index.json") + ": names \"" + entry.file +
             "\", not a .mgraph file in the export's folder";
    if (!named.insert(entry.file).second)
      return shown("index.json") + ": names " + entry.file + " for two materials";
    if (!graphs.count(entry.file))
      return shown("index.json") + ": names " + entry.file + ", which the export does not hold";
  }
  for (const auto& graph : graphs) {
    if (!named.count(graph))
      return shown(graph) + ": a graph that index.json does not name";
  }
  if (!expected.reportedMaterials) {
    return shown("") +
           ": the exporter printed no summary (\"memograph: wrote N material(s)\"): did Blender "
           "run the exporter script?";
  }
  if (index.size() < *expected.reportedMaterials) {
    return shown("index.json") + ": names " + std::to_string(index.size()) +
           " material(s), but the exporter reported " + std::to_string(*expected.reportedMaterials);
  }

  // Every graph parses, and declares the material the index gives it.
  for (const auto& entry : index) {
    const auto text =
        files::readInputFile(staging / entry.file, limits.maxGraphBytes, "graphs", error);
    if (!text)
      return shown(entry.file) + ": " + error;
    compiler::Diagnostics diagnostics;
    const compiler::SourceFile source{shown(entry.file), *text};
    const compiler::Graph graph = compiler::parseGraph(source, diagnostics);
    if (diagnostics.hasErrors()) {
      std::string message = compiler::formatDiagnostics(diagnostics);
      while (!message.empty() && message.back() == '\n')
        message.pop_back();
      return message;
    }
    if (graph.name != entry.material) {
      return shown(entry.file) + ": declares material '" + graph.name + "' but index.json says '" +
             entry.material + "'";
    }
  }

  if (expected.scene) {
    for (const char* name : {"scene.gltf", "scene.memograph"}) {
      if (!sizes.count(name))
        return shown(name) + ": missing: --scene was asked for";
    }
  }
  return {};
}

}  // namespace memograph::cli
