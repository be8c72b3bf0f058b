// Diagnostics are values: every pass appends to a Diagnostics list instead of throwing, and
// the driver prints them as `file:line:col: error: message` with the line and a caret.
#pragma once

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
  std::string sourceLine;          // copy of the offending line, for the caret display
  std::vector<std::string> notes;  // extra lines: candidates, the cycle, a fix
};

class Diagnostics {
 public:
  // Reports at a place in `file`; the line text is copied so the list outlives the file.
  Diagnostic& error(const SourceFile& file, SourceLocation at, std::string message);
  Diagnostic& warning(const SourceFile& file, SourceLocation at, std::string message);
  // Reports without a source position (e.g. a file that cannot be read).
  Diagnostic& error(std::string file, std::string message);

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
};

// `file:line:col: error: message`, then the source line, a caret under the column, and the
// notes, each on its own line. Ends with a newline.
std::string formatDiagnostic(const Diagnostic& diagnostic);
std::string formatDiagnostics(const Diagnostics& diagnostics);

}  // namespace memograph::compiler
