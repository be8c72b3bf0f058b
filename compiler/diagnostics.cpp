#include "compiler/diagnostics.h"

namespace memograph::compiler {

Diagnostic& Diagnostics::add(Severity severity, const SourceFile& file, SourceLocation at,
                             std::string message) {
  Diagnostic& d = items_.emplace_back();
  d.severity = severity;
  d.file = file.path;
  d.location = at;
  d.message = std::move(message);
  d.sourceLine = std::string(file.lineText(at.line));
  if (severity == Severity::Error)
    ++errorCount_;
  return d;
}

Diagnostic& Diagnostics::error(const SourceFile& file, SourceLocation at, std::string message) {
  return add(Severity::Error, file, at, std::move(message));
}

Diagnostic& Diagnostics::warning(const SourceFile& file, SourceLocation at, std::string message) {
  return add(Severity::Warning, file, at, std::move(message));
}

Diagnostic& Diagnostics::error(std::string file, std::string message) {
  Diagnostic& d = items_.emplace_back();
  d.file = std::move(file);
  d.message = std::move(message);
  ++errorCount_;
  return d;
}

void Diagnostics::append(const Diagnostics& other) {
  items_.insert(items_.end(), other.items_.begin(), other.items_.end());
  errorCount_ += other.errorCount_;
}

std::string formatDiagnostic(const Diagnostic& d) {
  std::string out = d.file;
  if (d.location.line > 0) {
    out += ':' + std::to_string(d.location.line) + ':' + std::to_string(d.location.column);
  }
  switch (d.severity) {
    case Severity::Error:
      out += ": error: ";
      break;
    case Severity::Warning:
      out += ": warning: ";
      break;
    case Severity::Note:
      out += ": note: ";
      break;
  }
  out += d.message;
  out += '\n';
  if (d.location.line > 0 && !d.sourceLine.empty()) {
    out += "    " + d.sourceLine + '\n';
    std::string caret = "    ";
    // Tabs stay tabs so the caret lines up with the source as the terminal shows it.
    for (std::uint32_t i = 1; i < d.location.column && i - 1 < d.sourceLine.size(); ++i) {
      caret += d.sourceLine[i - 1] == '\t' ? '\t' : ' ';
    }
    out += caret + "^\n";
  }
  for (const auto& note : d.notes)
    out += "    " + note + '\n';
  return out;
}

std::string formatDiagnostics(const Diagnostics& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics.all())
    out += formatDiagnostic(d);
  return out;
}

}  // namespace memograph::compiler
