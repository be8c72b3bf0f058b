// Shared pieces of the memograph commands: argument scanning, the node library, files.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/node_library.h"
#include "memograph/node_library_loader.h"

namespace memograph::cli {

using nodes::loadNodeLibrary;  // the node library: embedded, or `--nodes DIR`

// Exit codes: 0 success, 1 the input was bad or something failed, 2 the command line was.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

// A usage error: prints "memograph <command>: message" and a pointer to --help.
int usageError(std::string_view command, std::string_view message);

// A whole number in 0..2^32-1, all of `text`: true and `out` set, or false.
bool parseNumber(std::string_view text, std::uint32_t& out);
// A finite real number, all of `text` ("1.5", "-2", "1e-3"): true and `out` set, or false.
bool parseReal(std::string_view text, double& out);

// An image size "WxH" for render and bench: each side 1..kMaxImageSide, and at most
// files::kMaxImagePixels pixels (docs/limits.md). False with `error` saying why.
constexpr std::uint32_t kMaxImageSide = 16384;
bool parseImageSize(std::string_view text, std::uint32_t& width, std::uint32_t& height,
                    std::string& error);

// Walks `args`: options with a value (`--target glsl` or `--target=glsl`), flags, and
// positional arguments. Unknown options, and options without a value or with an empty one,
// are usage errors.
class ArgumentScanner {
 public:
  ArgumentScanner(std::string_view command, std::span<const std::string_view> args)
      : command_(command), args_(args) {}

  // Registers an option taking a value; `out` receives it.
  void option(std::string_view name, std::string* out) { options_.push_back({name, out, nullptr}); }
  void flag(std::string_view name, bool* out) { options_.push_back({name, nullptr, out}); }

  // Returns kExitOk and fills `positional`, or the exit code of a usage error (printed).
  int scan(std::vector<std::string>& positional);
  // Whether the scanned arguments gave option or flag `name`.
  bool given(std::string_view name) const;

 private:
  struct Option {
    std::string_view name;
    std::string* value;
    bool* flag;
  };
  std::string_view command_;
  std::span<const std::string_view> args_;
  std::vector<Option> options_;
  std::vector<std::string_view> given_;  // registered names, as scan() met them
};

// The note `render` and `bench` print for an option the chosen modes leave unused (it is
// accepted: a script may pass one set of flags to every mode it measures):
// "--x is ignored: it needs <needs>".
std::string ignoredOptionNote(std::string_view option, std::string_view needs);

// A text input (graph): a regular file of at most files::kMaxTextFileBytes, or nullopt
// with `error` saying why (without the path: callers' diagnostics name it).
std::optional<std::string> readFile(const std::string& path, std::string& error);

// Writes every (path, contents) pair or none (files::writeFileSet): unique temporaries,
// then renamed as a set under a lock on the folder, with the previous versions restored
// if a rename fails part-way.
bool writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files,
                          std::string& error);

// Checks, before any work, that `path` can be written as an output file (files::
// checkOutputPath: not a folder, in an existing folder). kExitOk, or kExitFailure after
// printing "memograph <command>: <path>: <why>".
int checkOutputFile(std::string_view command, const std::string& path);

void printDiagnostics(const compiler::Diagnostics& diagnostics);

}  // namespace memograph::cli
