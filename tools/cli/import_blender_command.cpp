// memograph import-blender SCENE.blend --out DIR [--blender PATH] [--materials NAME...]:
// runs Blender headless with the memograph exporter (tools/blender/export_memograph.py) and
// writes one .mgraph per material into DIR (docs/guide/blender.md). DIR is committed as a set
// (docs/guide/limits.md): Blender exports into a staging folder beside DIR, and only a
// complete, successful export that passes validateStagedExport (staged_import.h) reaches DIR.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "child_process.h"
#include "cli_common.h"
#include "commands.h"
#include "runtime/host/atomic_file.h"
#include "staged_import.h"

namespace memograph::cli {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kHelp =
    "usage: memograph import-blender SCENE.blend --out DIR [--blender PATH]\n"
    "                                [--materials NAME...] [--scene] [--verbose]\n"
    "                                [--timeout SECONDS]\n"
    "\n"
    "Exports the materials of a Blender file as memograph graphs: runs Blender headless\n"
    "(`blender -b SCENE.blend --python export_memograph.py -- --out DIR`) and writes one\n"
    ".mgraph per material into DIR, images into DIR/textures/ and DIR/index.json (Blender's\n"
    "material names -> graph files). Warnings (nodes memograph approximates or cannot carry)\n"
    "are printed on stderr. See docs/guide/blender.md.\n"
    "\n"
    "options:\n"
    "  --out DIR            output folder (created); written only when the whole export\n"
    "                       succeeds: Blender writes into a staging folder beside it\n"
    "  --blender PATH       the Blender executable (default: `blender` on PATH)\n"
    "  --materials NAME...  only these materials (default: all)\n"
    "  --timeout SECONDS    stop Blender (and what it started) after this long and fail\n"
    "                       (default 600; 0: no limit)\n"
    "  --scene              also write the scene: DIR/scene.gltf (Blender's glTF exporter,\n"
    "                       lights and active camera) and DIR/scene.memograph (what glTF\n"
    "                       drops: world, area lights, texture spaces); then\n"
    "                       `memograph render DIR/scene.gltf --materials DIR` renders it\n"
    "  --verbose            also show Blender's own output\n"
    "\n"
    "Before anything reaches DIR the export is checked: only regular files and folders, each\n"
    "within the size limits of docs/guide/limits.md, index.json naming exactly the graphs\n"
    "present, every graph parsing; otherwise DIR is left as it was.\n"
    "\n"
    "exit status: 0 written (warnings allowed), 1 Blender is missing, fails, times out or\n"
    "leaves an export that fails the check, the .blend cannot be read or a material cannot\n"
    "be exported, 2 a usage error, 128+N when stopped by signal N (SIGINT, SIGTERM,\n"
    "SIGHUP: Blender is stopped and nothing is left behind).\n";

// The directory of the running binary (for the installed/build-tree exporter script).
std::optional<fs::path> executableDir() {
  std::error_code ec;
  auto self = fs::read_symlink("/proc/self/exe", ec);
  if (ec)
    return std::nullopt;
  return self.parent_path();
}

// Where the exporter script is, in order: $MEMOGRAPH_BLENDER_EXPORTER; beside the binary in
// a build tree (<build>/tools/blender/, copied by tools/blender/CMakeLists.txt); installed
// (<prefix>/share/memograph/blender/); the source tree this binary was configured from.
// A MEMOGRAPH_BLENDER_EXPORTER that names no regular file is an error of its own (the
// user asked for that script), never a silent fall back to another one.
std::optional<fs::path> findExporterScript(std::vector<std::string>& tried) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("MEMOGRAPH_BLENDER_EXPORTER"); env && *env) {
    std::error_code ec;
    if (!fs::is_regular_file(env, ec)) {
      tried.push_back(std::string("MEMOGRAPH_BLENDER_EXPORTER=") + env + " (" +
                      (fs::exists(env, ec) ? "not a regular file" : "no such file") + ")");
      return std::nullopt;
    }
    return fs::weakly_canonical(env, ec);
  }
  if (auto dir = executableDir()) {
    candidates.push_back(*dir / "blender" / "export_memograph.py");
    candidates.push_back(*dir / ".." / "share" / "memograph" / "blender" / "export_memograph.py");
  }
#ifdef MEMOGRAPH_BLENDER_EXPORTER_SOURCE
  candidates.emplace_back(MEMOGRAPH_BLENDER_EXPORTER_SOURCE);
#endif
  for (const auto& c : candidates) {
    tried.push_back(c.string());
    std::error_code ec;
    if (fs::is_regular_file(c, ec))
      return fs::weakly_canonical(c, ec);
  }
  return std::nullopt;
}

bool isExecutableFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && ::access(path.c_str(), X_OK) == 0;
}

std::optional<fs::path> findOnPath(const std::string& name) {
  if (name.find('/') != std::string::npos)
    return isExecutableFile(name) ? std::optional<fs::path>(name) : std::nullopt;
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/local/bin:/usr/bin:/bin";
  while (true) {
    auto colon = rest.find(':');
    std::string dir(rest.substr(0, colon));
    fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    if (isExecutableFile(candidate))
      return candidate;
    if (colon == std::string_view::npos)
      break;
    rest.remove_prefix(colon + 1);
  }
  return std::nullopt;
}

// Checks the file header so that a wrong file gets a clear error before Blender starts
// (Blender would print its own message and go on with an empty scene). A .blend starts
// with "BLENDER"; saved compressed it is gzip (Blender < 3.0) or Zstandard (3.0+).
std::string checkBlendFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec))
    return "no such file";
  if (!fs::is_regular_file(path, ec))
    return "not a regular file";
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 7> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  if (in.gcount() < 4)
    return "not a .blend file (too short)";
  if (std::memcmp(head.data(), "BLENDER", 7) == 0)
    return {};
  if (head[0] == 0x1f && head[1] == 0x8b)
    return {};  // gzip
  if (head[0] == 0x28 && head[1] == 0xb5 && head[2] == 0x2f && head[3] == 0xfd)
    return {};  // zstd
  return "not a .blend file (no BLENDER header)";
}

// Blender's own stdout is mostly a banner and "Read blend:"; show only what matters
// unless --verbose: the exporter's summary and Blender's error lines (a bad .blend).
bool interestingBlenderLine(std::string_view line) {
  for (std::string_view prefix :
       {"memograph:", "error:", "Error", "ERROR", "Warning: unable", "Traceback", "Segmentation"}) {
    if (line.substr(0, prefix.size()) == prefix)
      return true;
  }
  return false;
}

constexpr std::string_view kCommand = "memograph import-blender: ";

// Folders this command created (the output folder's missing parents, folders inside DIR):
// removed again, deepest first and only while empty, when the command fails.
class CreatedFolders {
 public:
  ~CreatedFolders() {
    if (keep_)
      return;
    for (auto it = folders_.rbegin(); it != folders_.rend(); ++it) {
      std::error_code ignored;
      fs::remove(*it, ignored);  // only an empty folder is removed
    }
  }
  // create_directories, remembering each folder it made.
  bool create(const fs::path& folder, std::string& error) {
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path at = folder; !at.empty() && !fs::exists(fs::symlink_status(at, ec));
         at = at.parent_path()) {
      missing.push_back(at);
      if (at == at.parent_path())
        break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      const bool made = fs::create_directory(*it, ec);
      if (ec) {
        error = it->string() + ": cannot create the folder: " + ec.message();
        return false;
      }
      if (made)  // not one that appeared meanwhile
        folders_.push_back(*it);
    }
    return true;
  }
  void keep() { keep_ = true; }

 private:
  std::vector<fs::path> folders_;
  bool keep_ = false;
};

// The folder Blender exports into: `.<DIR name>.import-<pid>-XXXXXX` beside DIR (so on
// DIR's file system, and renamed into place when DIR does not exist yet). Removed with
// everything in it unless released. The pid in the name lets a later run tell a folder
// left by a process that was killed (SIGKILL, a crash, a power cut) from one in use.
class StagingFolder {
 public:
  ~StagingFolder() {
    if (path_.empty())
      return;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  bool create(const fs::path& target, std::string& error) {
    removeStale(target);
    std::string pattern = (target.parent_path() / prefix(target)).string();
    pattern += std::to_string(::getpid());
    pattern += "-XXXXXX";
    if (!::mkdtemp(pattern.data())) {
      error =
          files::errnoMessage("cannot create a staging folder beside " + target.string(), errno);
      return false;
    }
    path_ = pattern;
    // mkdtemp makes it 0700; the output folder gets what mkdir(2) would have given it.
    const mode_t mask = ::umask(022);
    ::umask(mask);
    ::chmod(path_.c_str(), 0777 & ~mask);
    return true;
  }
  const fs::path& path() const { return path_; }
  void release() { path_.clear(); }

 private:
  static std::string prefix(const fs::path& target) {
    std::string name = ".";  // appended: GCC 12 warns falsely (-Wrestrict) on "." + string
    name += target.filename().string();
    name += ".import-";
    return name;
  }

  // The pid in `name` when it is exactly prefix + <pid>-XXXXXX (mkdtemp's six characters).
  static std::optional<pid_t> stagingPid(std::string_view name, std::string_view prefix) {
    if (name.substr(0, prefix.size()) != prefix)
      return std::nullopt;
    name.remove_prefix(prefix.size());
    pid_t pid = 0;
    const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), pid);
    const std::string_view rest(end, std::size_t(name.data() + name.size() - end));
    if (ec != std::errc() || end == name.data() || pid <= 0 || rest.size() != 7 || rest[0] != '-')
      return std::nullopt;
    for (const char c : rest.substr(1)) {
      if (!std::isalnum(static_cast<unsigned char>(c)))
        return std::nullopt;
    }
    return pid;
  }

  // Removes the staging folders of this DIR that earlier runs left when they were killed:
  // only real folders (not links) of exactly our name pattern, owned by us, whose process
  // is gone. A live pid (ours, another import, or a reused one) keeps its folder.
  static void removeStale(const fs::path& target) {
    const std::string wanted = prefix(target);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(target.parent_path(), ec)) {
      const std::string name = entry.path().filename().string();
      const auto pid = stagingPid(name, wanted);
      if (!pid || *pid == ::getpid())
        continue;
      struct stat info {};
      if (::lstat(entry.path().c_str(), &info) != 0 || !S_ISDIR(info.st_mode) ||
          info.st_uid != ::geteuid())
        continue;
      if (::kill(*pid, 0) == 0 || errno != ESRCH)
        continue;
      std::error_code removeError;
      fs::remove_all(entry.path(), removeError);
      if (!removeError)
        std::cerr << kCommand << "removed " << entry.path().string()
                  << ", left by an import (process " << *pid << ") that was stopped\n";
    }
  }

  fs::path path_;
};

// Commits the staged export into `target`, which exists: every file is staged next to its
// target (files::StagedFile, moved there from the staging folder) and all are renamed into
// place as one set (files::commitFileSet): a failure part-way restores what was replaced.
bool commitIntoFolder(const fs::path& staging, const fs::path& target, CreatedFolders& created,
                      std::string& error) {
  // The listing first: files are moved out of the staging folder below.
  std::vector<std::pair<fs::path, fs::file_status>> entries;
  std::error_code ec;
  fs::recursive_directory_iterator it(staging, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const fs::file_status status = it->symlink_status(ec);
    if (!ec)
      entries.emplace_back(it->path(), status);
  }
  if (ec) {
    error = staging.string() + ": cannot read the staged export: " + ec.message();
    return false;
  }
  std::vector<files::StagedFile> staged;
  for (const auto& [path, status] : entries) {
    const fs::path destination = target / path.lexically_relative(staging);
    if (fs::is_directory(status)) {  // listed before what it holds
      const fs::file_status there = fs::status(destination, ec);
      if (fs::exists(there) && !fs::is_directory(there)) {
        error = destination.string() + ": is a file; the export has a folder there";
        return false;
      }
      if (!fs::exists(there) && !created.create(destination, error))
        return false;
      continue;
    }
    if (!fs::is_regular_file(status)) {
      error = path.string() + ": the export wrote something that is not a regular file";
      return false;
    }
    files::StagedFile file;
    std::string cause;
    if (!file.create(destination, cause) || !file.adopt(path, cause)) {
      error = destination.string() + ": " + cause;
      return false;
    }
    staged.push_back(std::move(file));
  }
  return files::commitFileSet(staged, error);
}

// The Blender executable: --blender's, or `blender` on PATH; nullopt after saying why not.
std::optional<fs::path> findBlender(const std::string& blender) {
  if (!blender.empty()) {
    auto path = findOnPath(blender);
    if (!path)
      std::cerr << kCommand << "--blender " << blender << ": not an executable file\n";
    return path;
  }
  auto path = findOnPath("blender");
  if (!path)
    std::cerr << kCommand
              << "Blender was not found on PATH. Install it (Debian: `apt install blender`; "
                 "tools/setup.sh does) or pass --blender PATH.\n";
  return path;
}

// The exporter script; nullopt after listing where it was looked for.
std::optional<fs::path> findExporter() {
  std::vector<std::string> tried;
  auto script = findExporterScript(tried);
  if (!script && std::getenv("MEMOGRAPH_BLENDER_EXPORTER") &&
      *std::getenv("MEMOGRAPH_BLENDER_EXPORTER")) {
    std::cerr << kCommand << "the exporter script " << tried.front()
              << "; unset it to use the installed export_memograph.py\n";
  } else if (!script) {
    std::cerr << kCommand << "the exporter script export_memograph.py was not found; looked at:\n";
    for (const auto& t : tried)
      std::cerr << "  " << t << "\n";
    std::cerr << "set MEMOGRAPH_BLENDER_EXPORTER to its path\n";
  }
  return script;
}

// The output folder, absolute and without a trailing separator (its name names the
// staging folder). A file there, or a dangling link, is an error before Blender starts.
std::optional<fs::path> outputFolder(const std::string& outDir) {
  std::error_code ec;
  fs::path absOut = fs::absolute(outDir, ec).lexically_normal();
  if (absOut.has_relative_path() && absOut.filename().empty())
    absOut = absOut.parent_path();
  const fs::file_status outStatus = fs::status(absOut, ec);
  if (fs::exists(outStatus) && !fs::is_directory(outStatus)) {
    std::cerr << kCommand << "--out " << outDir << ": is a file, not a folder\n";
    return std::nullopt;
  }
  if (!fs::exists(outStatus) && fs::is_symlink(fs::symlink_status(absOut, ec))) {
    std::cerr << kCommand << "--out " << outDir << ": is a dangling symbolic link\n";
    return std::nullopt;
  }
  return absOut;
}

struct ImportArguments {
  std::string outDir, blender, timeout = "600";
  std::vector<std::string> positional, materials;
  bool verbose = false, withScene = false;
};

// What Blender's run left to check the export against.
struct BlenderRun {
  int exitCode = kExitFailure;
  StagedExportExpectation expected;
};

// Runs Blender (`argv`) with its stdout shown line by line (stderr, where the exporter's
// warnings go, is shared): the lines that matter, or all with --verbose, the staging
// folder's name shown as the output folder's. Blender is stopped after `timeout` (0: never)
// and when we get SIGINT, SIGTERM or SIGHUP (exit code 128 + the signal).
BlenderRun runBlender(const std::vector<std::string>& argv, const std::string& stagingName,
                      const fs::path& absOut, std::chrono::milliseconds timeout, bool verbose) {
  BlenderRun run;
  auto asOutput = [&](std::string text) {
    for (std::size_t at = 0; (at = text.find(stagingName, at)) != std::string::npos;) {
      text.replace(at, stagingName.size(), absOut.string());
      at += absOut.string().size();
    }
    return text;
  };
  auto show = [&](const std::string& line) { std::cout << asOutput(line) << "\n" << std::flush; };
  ChildOptions options;
  options.timeout = timeout;
  options.onLine = [&](std::string_view line, bool cut) {
    if (!cut) {
      if (const auto count = parseExportSummary(line))
        run.expected.reportedMaterials = count;
    }
    if (verbose || interestingBlenderLine(line))
      show(std::string(line) + (cut ? " [... line cut]" : ""));
  };
  const ChildResult child = runChild(argv, options);
  const std::string unchanged = "; " + absOut.string() + " is unchanged";
  auto showTail = [&] {
    if (verbose || child.tail.empty())
      return;
    std::cerr << kCommand << "the end of Blender's output:\n";
    std::string tail = asOutput(child.tail);
    if (tail.back() != '\n')
      tail += '\n';
    std::cerr << tail;
  };
  switch (child.ending) {
    case ChildResult::Ending::NotStarted:
      std::cerr << kCommand << child.error << "\n";
      return run;
    case ChildResult::Ending::Interrupted:
      std::cerr << kCommand << "stopped by signal " << child.signal << " ("
                << strsignal(child.signal) << "): Blender was stopped" << unchanged << "\n";
      run.exitCode = 128 + child.signal;
      return run;
    case ChildResult::Ending::TimedOut:
      showTail();
      std::cerr << kCommand << "Blender did not finish within --timeout "
                << std::chrono::duration_cast<std::chrono::seconds>(timeout).count()
                << " s and was stopped" << unchanged << "\n";
      return run;
    case ChildResult::Ending::Signalled:
      showTail();
      std::cerr << kCommand << "Blender ended with signal " << child.signal << " ("
                << strsignal(child.signal) << ")" << unchanged << "\n";
      return run;
    case ChildResult::Ending::Exited:
      if (child.exitCode != 0) {
        std::cerr << kCommand << "the export failed (Blender exit status " << child.exitCode << ")"
                  << unchanged << "\n";
        return run;
      }
      run.exitCode = kExitOk;
      return run;
  }
  return run;
}

// A new output folder: the staging folder is renamed into place (atomic). One that exists
// (or appeared meanwhile) takes the exported files as one set.
int commitExport(StagingFolder& staging, const fs::path& absOut, CreatedFolders& created,
                 const StagedExportExpectation& expected) {
  if (const std::string problem = validateStagedExport(staging.path(), absOut, expected);
      !problem.empty()) {
    std::cerr << kCommand << "the export is refused: " << problem << "\n"
              << kCommand << absOut.string() << " is unchanged\n";
    return kExitFailure;
  }
  std::error_code ec;
  if (!fs::exists(absOut, ec)) {
    if (::rename(staging.path().c_str(), absOut.c_str()) == 0) {
      staging.release();
      created.keep();
      return kExitOk;
    }
    if (errno != EEXIST && errno != ENOTEMPTY) {
      std::cerr << kCommand
                << files::errnoMessage(absOut.string() + ": cannot move the export into place",
                                       errno)
                << "\n";
      return kExitFailure;
    }
  }
  std::string error;
  if (!commitIntoFolder(staging.path(), absOut, created, error)) {
    std::cerr << kCommand << error << "; " << absOut.string() << " is unchanged\n";
    return kExitFailure;
  }
  created.keep();
  return kExitOk;
}

std::optional<int> scanImportArguments(std::span<const std::string_view> args, ImportArguments& a) {
  ArgumentScanner scanner("import-blender", args);
  scanner.option("--out", &a.outDir);
  scanner.option("--blender", &a.blender);
  scanner.option("--timeout", &a.timeout);
  scanner.list("--materials", &a.materials);
  scanner.flag("--verbose", &a.verbose);
  scanner.flag("--scene", &a.withScene);
  scanner.help(kHelp);
  if (const auto exitCode = scanner.scan(a.positional))
    return exitCode;
  if (a.positional.size() != 1)
    return usageError("import-blender", a.positional.empty() ? "no .blend file given"
                                                             : "give exactly one .blend file");
  if (a.outDir.empty())
    return usageError("import-blender", "--out DIR is required");
  double seconds = 0;
  if (!parseReal(a.timeout, seconds) || !std::isfinite(seconds) || seconds < 0 || seconds > 1e7)
    return usageError("import-blender",
                      "--timeout takes seconds from 0 (no limit) to 1e7, not '" + a.timeout + "'");
  return std::nullopt;
}

}  // namespace

int runImportBlender(std::span<const std::string_view> args) {
  ImportArguments a;
  if (const auto exitCode = scanImportArguments(args, a))
    return *exitCode;
  const fs::path blend = a.positional[0];
  if (const int code =
          refuseOutputOverInput("import-blender", {{"--out", a.outDir}},
                                {{"SCENE.blend", blend.string()}, {"--blender", a.blender}});
      code != kExitOk)
    return code;
  if (auto problem = checkBlendFile(blend); !problem.empty()) {
    std::cerr << kCommand << blend.string() << ": " << problem << "\n";
    return kExitFailure;
  }
  const std::optional<fs::path> blenderPath = findBlender(a.blender);
  if (!blenderPath)
    return kExitFailure;
  const std::optional<fs::path> script = findExporter();
  if (!script)
    return kExitFailure;
  const std::optional<fs::path> absOut = outputFolder(a.outDir);
  if (!absOut)
    return kExitFailure;
  CreatedFolders created;
  StagingFolder staging;
  std::string error;
  if (!created.create(absOut->parent_path(), error) || !staging.create(*absOut, error)) {
    std::cerr << kCommand << error << "\n";
    return kExitFailure;
  }
  const std::string stagingName = staging.path().string();
  std::error_code ec;
  std::vector<std::string> argv = {blenderPath->string(),
                                   "-b",
                                   "--factory-startup",
                                   fs::absolute(blend, ec).string(),
                                   "--python-exit-code",
                                   "1",
                                   "--python",
                                   script->string(),
                                   "--",
                                   "--out",
                                   stagingName};
  if (a.withScene)
    argv.emplace_back("--scene");
  if (!a.materials.empty()) {
    argv.emplace_back("--materials");
    argv.insert(argv.end(), a.materials.begin(), a.materials.end());
  }
  double seconds = 0;
  parseReal(a.timeout, seconds);
  const auto timeout = std::chrono::milliseconds(std::llround(seconds * 1000));
  const BlenderRun run = runBlender(argv, stagingName, *absOut, timeout, a.verbose);
  if (run.exitCode != kExitOk)
    return run.exitCode;
  StagedExportExpectation expectation = run.expected;
  expectation.scene = a.withScene;
  return commitExport(staging, *absOut, created, expectation);
}

}  // namespace memograph::cli
