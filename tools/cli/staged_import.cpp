#include "tools/cli/staged_import.h"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/parser.h"
#include "compiler/source_file.h"
#include "runtime/host/atomic_file.h"
#include "tools/io/json_reader.h"

namespace memograph::cli {

namespace {

namespace fs = std::filesystem;

// One entry of index.json: Blender's material name -> its graph file and mgraph name.
struct IndexEntry {
  std::string file, material;
};

// Reads index.json in the one shape the exporter writes (exporter.py, export_materials):
// {"materials": {"<Blender name>": {"file": "<X>.mgraph", "material": "<X>"}, ...}}, any
// whitespace and key order. Anything else is an error with its byte offset: JSON that is
// not valid, or valid JSON of another shape (an unknown or repeated key, a missing field).
bool readIndex(std::string_view text, std::vector<IndexEntry>& entries, std::string& error) {
  const auto fail = [&](const std::string& message, std::size_t at) {
    error = message + " (at byte " + std::to_string(at) + ")";
    return false;
  };
  io::JsonError jsonError;
  const std::optional<io::JsonValue> root = io::readJson(text, jsonError);
  if (!root)
    return fail(jsonError.message, jsonError.offset);
  using Kind = io::JsonValue::Kind;
  if (root->kind != Kind::Object)
    return fail("expected '{'", root->offset);
  for (const auto& [key, value] : root->members) {
    if (key != "materials")
      return fail("unknown key \"" + key + "\" (only \"materials\")", value.offset);
  }
  if (const auto repeated = root->repeatedMember())
    return fail("\"materials\" given twice", root->members[*repeated].value.offset);
  const io::JsonValue* materials = root->get("materials");
  if (!materials)
    return fail("no \"materials\" object", root->offset);
  if (materials->kind != Kind::Object)
    return fail("expected '{'", materials->offset);
  if (const auto repeated = materials->repeatedMember()) {
    const io::JsonMember& member = materials->members[*repeated];
    return fail("material \"" + member.key + "\" listed twice", member.value.offset);
  }
  for (const auto& [blenderName, fields] : materials->members) {
    if (fields.kind != Kind::Object)
      return fail("expected '{'", fields.offset);
    IndexEntry entry;
    for (const auto& [key, value] : fields.members) {
      std::string* field = key == "file"       ? &entry.file
                           : key == "material" ? &entry.material
                                               : nullptr;
      if (!field)
        return fail("unknown key \"" + key + "\" (only \"file\" and \"material\")", value.offset);
      if (value.kind != Kind::String)
        return fail("expected a string", value.offset);
      *field = value.string;
    }
    if (const auto repeated = fields.repeatedMember()) {
      const io::JsonMember& member = fields.members[*repeated];
      return fail("material \"" + blenderName + "\" gives \"" + member.key + "\" twice",
                  member.value.offset);
    }
    if (entry.file.empty() || entry.material.empty())
      return fail("material \"" + blenderName + "\" lacks \"file\" or \"material\"", fields.offset);
    entries.push_back(std::move(entry));
  }
  return true;
}

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
  if (!readIndex(*indexText, index, error))
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
