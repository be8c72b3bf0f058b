// The project's one way to write output files: all of a file or none of it, and all of a
// set of files or none of them, even with several processes writing the same paths.
//
// Every file is first written to a temporary created with a unique name (mkstemp) in the
// target's own folder, so the final rename(2) never crosses a file system and is atomic;
// two processes never share a temporary (mkstemp's random part makes the name unique: a
// fixed, pid- or time-based name alone collides). The name also carries the writer's pid,
// so that temporaries of a process that was killed (SIGKILL leaves no chance to remove
// them) are found and removed by the next write into that folder. A set of files (`compile`'s
// folder) is committed under an exclusive flock(2) on the target folder, the previous version of
// each file kept aside as a hard link, so that a failure part-way through restores every file
// already replaced and concurrent commits into one folder do not interleave. Standard library and
// POSIX only: the core (PFM, the shader cache), the io library and the CLI all use it.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace memograph::files {

// A temporary file next to `target`, created empty and exclusively (mode 0666 & ~umask),
// removed by the destructor unless committed: `.<stem>.partial-<pid>@<host>-XXXXXX<ext>`. The
// name keeps the target's extension, so libraries that pick a format by extension
// (OpenImageIO) can write it by path. The first create() in a folder (once per process)
// removes the temporaries there of processes of this host that no longer exist.
class StagedFile {
 public:
  StagedFile() = default;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&& other) noexcept;
  ~StagedFile();

  // Creates the temporary; false with `error` (naming the cause, from errno) on failure.
  bool create(const std::filesystem::path& target, std::string& error);
  // Writes all of `bytes` to the temporary and flushes it to the disk (fsync), so a full
  // disk is found here and not after the rename.
  bool write(std::string_view bytes, std::string& error);
  // Checks a temporary written by someone else through temporaryPath(): present, flushed.
  bool sync(std::string& error);
  // Takes `written`, a complete file written elsewhere (a staging folder), as the
  // temporary: renamed over it when both are on one file system, else copied; then
  // flushed. `written` is gone afterwards only when it was renamed.
  bool adopt(const std::filesystem::path& written, std::string& error);
  // Renames the temporary over the target.
  bool commit(std::string& error);
  // Removes the temporary (the destructor does this too).
  void discard();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

 private:
  bool writeAll(std::string_view bytes, std::string& error);  // to fd_, without fsync

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  bool committed_ = false;
};

// Writes `bytes` to `path` atomically. `error` is "<cause>" without the path.
bool writeFileAtomically(const std::filesystem::path& path, std::string_view bytes,
                         std::string& error);

// Writes a file through `writeTo(temporaryPath, error)` (for writers that open files by
// name) and renames it into place when it returns true.
bool writeFileAtomicallyWith(
    const std::filesystem::path& path,
    const std::function<bool(const std::filesystem::path& temporary, std::string& error)>& writeTo,
    std::string& error);

// Commits files already staged (and written) as a set: all are renamed into place or,
// if one rename fails, the ones already renamed get their previous versions back (or are
// removed when they were new). `error` names the file that failed.
bool commitFileSet(std::vector<StagedFile>& staged, std::string& error);

// Writes every (path, bytes) pair or none: all are staged first, then committed as a set.
// `error` names the file that failed.
bool writeFileSet(const std::vector<std::pair<std::string, std::string>>& files,
                  std::string& error);

// Checks, before any work, that `path` can be an output file: not a folder, its folder
// exists and is a folder. `error` says what is wrong (without the path).
bool checkOutputPath(const std::filesystem::path& path, std::string& error);

// "<what>: <strerror(errnoValue)>", never "Success": a zero errno becomes "unknown error".
std::string errnoMessage(std::string_view what, int errnoValue);

}  // namespace memograph::files
