// Shared pieces of the memograph commands: argument scanning, the node library, files.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
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
// files::kMaxImagePixels pixels (docs/guide/limits.md). False with `error` saying why.
constexpr std::uint32_t kMaxImageSide = 16384;
bool parseImageSize(std::string_view text, std::uint32_t& width, std::uint32_t& height,
                    std::string& error);

// Walks `args`: options with a value (`--target glsl` or `--target=glsl`), options with a
// list of values, flags, and positional arguments. Unknown options, and options without a
// value or with an empty one, are usage errors.
class ArgumentScanner {
 public:
  ArgumentScanner(std::string_view command, std::span<const std::string_view> args)
      : command_(command), args_(args) {}

  // Registers an option taking a value; `out` receives it.
  void option(std::string_view name, std::string* out) {
    options_.push_back({name, out, nullptr, nullptr});
  }
  void flag(std::string_view name, bool* out) { options_.push_back({name, nullptr, out, nullptr}); }
  // Registers an option taking one or more values: those after it up to the next argument
  // that starts with '-' (`--materials A B`), or the one after '=' (`--materials=A`); each
  // use appends to `out`.
  void list(std::string_view name, std::vector<std::string>* out) {
    options_.push_back({name, nullptr, nullptr, out});
  }
  // Registers --help and -h: scan() then prints `text` (or the parts, one after the other)
  // and stops the command (kExitOk).
  void help(std::string_view text) { help({text}); }
  void help(std::initializer_list<std::string_view> parts) {
    help_.emplace();
    for (const std::string_view part : parts)
      help_->append(part);
  }

  // Fills `positional` and returns nullopt for the command to go on, or the exit code it
  // returns now: a usage error's (printed), or kExitOk when the help was asked for (printed;
  // a usage error wins over it).
  std::optional<int> scan(std::vector<std::string>& positional);
  // Whether the scanned arguments gave option or flag `name`.
  bool given(std::string_view name) const;

 private:
  struct Option {
    std::string_view name;
    std::string* value;
    bool* flag;
    std::vector<std::string>* list;
  };
  std::string_view command_;
  std::span<const std::string_view> args_;
  std::vector<Option> options_;
  std::optional<std::string> help_;
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

// A file a command reads or writes, named as its command line names it: `role` is the
// option or argument ("--out", "REFERENCE", "--materials graph").
struct CommandFile {
  std::string role;
  std::string path;
};

// The files of folder input `folder` that a command reads: those ending in `extension`, in
// the folder itself or, with `recursive`, below it too (a node library's .inc files, a
// scene's .mgraph graphs). Each becomes an input of `role`; a folder that cannot be listed
// adds none (reading it reports the problem). At most kMaxFolderInputs files are listed.
constexpr std::size_t kMaxFolderInputs = 100000;
void addFolderInputs(std::vector<CommandFile>& inputs, std::string_view role,
                     const std::string& folder, std::string_view extension, bool recursive);

// Refuses, before any output is created, a command line whose output is one of its inputs
// (`diff A B --out A` would replace A with the error map) or whose two outputs name one
// file. Paths are compared as files: through symbolic links (a link to an input is the
// input), and by device and inode where both exist (a hard link is the input too). kExitOk,
// or kExitUsage after printing "memograph <command>: <role> 'out' is <role> 'in' ...".
// Empty paths are skipped, so options not given may be passed as they are.
int refuseOutputOverInput(std::string_view command, const std::vector<CommandFile>& outputs,
                          const std::vector<CommandFile>& inputs);

// Checks `--device N` (`deviceIndex`; negative: not given) against this machine's Vulkan
// devices before any output or GPU work: an index past the last is a usage error (kExitUsage)
// whose message gives how many devices there are and lists them, as `render --list-devices`
// does. A machine with no device at all passes: the renderer then says which driver to
// install. Builds without the renderer pass every index.
int checkDeviceIndex(std::string_view command, int deviceIndex);

void printDiagnostics(const compiler::Diagnostics& diagnostics);

}  // namespace memograph::cli
