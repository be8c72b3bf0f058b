// libFuzzer entry point: bytes as a staging folder that an exporter left, checked by the
// validation `import-blender` runs before committing (cli::validateStagedExport). It must
// never crash or hang, and must refuse every folder that holds a link or a special file
// (checked here again, independently, for every folder it accepts).
//
// The input is split at "\n--\n" into parts. The first part is index.json; every other
// part is one entry whose first line says what it is and the rest is its content:
//   NAME        a regular file NAME (a path in the export, folders made as needed)
//   @NAME       a symbolic link NAME to the content
//   |NAME       a FIFO NAME
//   /NAME       an empty folder NAME
// Names are sanitized (no "..", no leading '/', at most 64 characters). The first byte of
// the input, before the index, picks the reported material count (0-3, or none when 4+)
// and whether --scene was asked for.
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tests/fuzz/fuzz_folder.h"
#include "tools/cli/staged_import.h"

namespace {

namespace fs = std::filesystem;

std::string root;

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> parts;
  constexpr std::string_view kSeparator = "\n--\n";
  while (true) {
    const std::size_t at = text.find(kSeparator);
    parts.push_back(text.substr(0, at));
    if (at == std::string_view::npos || parts.size() > 64)
      return parts;
    text.remove_prefix(at + kSeparator.size());
  }
}

// A relative path inside the staging folder, or empty when none can be made.
std::string sanitize(std::string_view name) {
  std::string out;
  for (char c : name.substr(0, 64)) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '.' || c == '_' || c == '-' || c == '/';
    out += plain ? c : '_';
  }
  std::string cleaned;
  for (const auto& part : fs::path(out)) {
    if (part == ".." || part == "." || part.empty() || part == "/")
      continue;
    if (!cleaned.empty())
      cleaned += '/';
    cleaned += part.string();
  }
  return cleaned;
}

// True when every folder between `staging` and `path` is a real folder or missing: a part
// never writes through a link an earlier part made (that could reach outside the folder).
bool insideWithoutLinks(const fs::path& staging, const fs::path& relative) {
  fs::path at = staging;
  for (const auto& part : relative.parent_path()) {
    at /= part;
    struct stat info {};
    if (::lstat(at.c_str(), &info) != 0)
      return true;  // missing: created as a folder below
    if (!S_ISDIR(info.st_mode))
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  root = memograph::fuzz::makePrivateFolder("staged");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::uint8_t settings = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const fs::path staging = fs::path(root) / "staging";
  std::error_code ec;
  fs::remove_all(staging, ec);
  fs::create_directories(staging, ec);

  const auto parts = split(text);
  memograph::fuzz::writeFile(staging / "index.json", parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    std::string_view part = parts[i];
    const std::size_t newline = part.find('\n');
    std::string_view head = part.substr(0, newline);
    const std::string_view body =
        newline == std::string_view::npos ? std::string_view() : part.substr(newline + 1);
    char kind = 'f';
    if (!head.empty() && (head[0] == '@' || head[0] == '|' || head[0] == '/')) {
      kind = head[0];
      head.remove_prefix(1);
    }
    const std::string name = sanitize(head);
    if (name.empty())
      continue;
    const fs::path path = staging / name;
    if (!insideWithoutLinks(staging, name))
      continue;
    fs::create_directories(path.parent_path(), ec);
    fs::remove_all(path, ec);
    if (kind == '@') {
      fs::create_symlink(std::string(body.substr(0, 200)), path, ec);
    } else if (kind == '|') {
      ::mkfifo(path.c_str(), 0600);
    } else if (kind == '/') {
      fs::create_directories(path, ec);
    } else {
      memograph::fuzz::writeFile(path, body);
    }
  }

  memograph::cli::StagedExportExpectation expected;
  if ((settings & 7) < 4)
    expected.reportedMaterials = settings & 3;
  expected.scene = (settings & 8) != 0;
  memograph::cli::StagedExportLimits limits;
  limits.maxGraphBytes = 64 * 1024;
  limits.maxFileBytes = 64 * 1024;
  limits.maxTotalBytes = 1024 * 1024;
  limits.maxEntries = 200;
  const std::string problem =
      memograph::cli::validateStagedExport(staging, "DIR", expected, limits);

  // Independent checks of what an accepted folder must be.
  if (problem.empty()) {
    for (const auto& entry : fs::recursive_directory_iterator(staging, ec)) {
      const auto status = entry.symlink_status(ec);
      if (!fs::is_regular_file(status) && !fs::is_directory(status)) {
        std::fprintf(stderr, "accepted %s, not a regular file or folder\n", entry.path().c_str());
        std::abort();
      }
    }
  }
  return 0;
}
