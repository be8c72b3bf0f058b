// Diagnostics are values: every pass appends to a Diagnostics list instead of throwing, and
// the driver prints them as `file:line:col: error: message` with the line and a caret.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "compiler/source_file.h"

namespace memograph::compiler {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string file;
  SourceLocation location;
  std::string message;
  // The offending line for the caret display: a copy of it, or of a window around the
  // column when the line is long (a 16 MiB one-line graph must not be copied per error).
  std::string sourceLine;
  std::uint32_t caretColumn = 0;   // 1-based column of the caret in sourceLine; 0: none
  std::vector<std::string> notes;  // extra lines: candidates, the cycle, a fix
};

class Diagnostics {
 public:
  // Reports at a place in `file`; the line text is copied so the list outlives the file.
  Diagnostic& error(const SourceFile& file, SourceLocation at, std::string message);
  Diagnostic& warning(const SourceFile& file, SourceLocation at, std::string message);
  // Reports without a source position (e.g. a file that cannot be read).
  Diagnostic& error(std::string file, std::string message);

  // Diagnostics kept per file. Past it they are still counted (hasErrors, errorCount) but
  // not kept, and one note says so: each kept one copies its source line, found by a scan
  // from the top of the file, so thousands of bad lines would cost quadratic time and memory.
  static constexpr std::size_t kMaxKeptPerFile = 100;
  // Longer lines are shown as a window of this many bytes around the column, and longer
  // messages keep their start and end: both may quote megabytes of a hostile input.
  static constexpr std::size_t kMaxShownLineBytes = 160;
  static constexpr std::size_t kMaxMessageBytes = 400;

  // Whether the next diagnostic for `file` will be kept: costly notes (did-you-mean) are
  // computed only then.
  bool keeps(const SourceFile& file) const;
  bool hasErrors() const { return errorCount_ > 0; }
  std::size_t errorCount() const { return errorCount_; }
  const std::vector<Diagnostic>& all() const { return items_; }
  Diagnostic& last() { return items_.back(); }  // to add notes; requires a diagnostic
  void append(const Diagnostics& other);

 private:
  Diagnostic& add(Severity severity, const SourceFile& file, SourceLocation at,
                  std::string message);
  std::vector<Diagnostic> items_;
  std::size_t errorCount_ = 0;
  struct FileCount {
    std::size_t kept = 0;
    std::size_t omitted = 0;
    std::size_t note = 0;  // index in items_ of the "and N more" note, once there is one
  };
  std::map<std::string, FileCount, std::less<>> perFile_;
  Diagnostic discarded_;  // what add() returns for a diagnostic past the limit
};

// `file:line:col: error: message`, then the source line, a caret under the column, and the
// notes, each on its own line. Ends with a newline.
std::string formatDiagnostic(const Diagnostic& diagnostic);
std::string formatDiagnostics(const Diagnostics& diagnostics);

}  // namespace memograph::compiler
