#include "compiler/diagnostics.h"

#include <algorithm>
#include <string_view>

namespace memograph::compiler {

namespace {

// UTF-8 continuation bytes are not cut through, so an excerpt stays valid text.
bool isContinuationByte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

// The start and the end of `message` when it is longer than `limit` bytes.
std::string shortened(std::string message, std::size_t limit) {
  if (message.size() <= limit)
    return message;
  std::size_t head = limit * 2 / 3;
  std::size_t tail = message.size() - (limit - head);
  while (head > 0 && isContinuationByte(message[head]))
    --head;
  while (tail < message.size() && isContinuationByte(message[tail]))
    ++tail;
  return message.substr(0, head) + "…(" + std::to_string(tail - head) + " bytes not shown)…" +
         message.substr(tail);
}

}  // namespace

Diagnostic& Diagnostics::add(Severity severity, const SourceFile& file, SourceLocation at,
                             std::string message) {
  if (severity == Severity::Error)
    ++errorCount_;
  FileCount& count = perFile_[file.path];
  if (count.kept >= kMaxKeptPerFile) {
    // Past the limit a problem is only counted; the note at the end says how many.
    ++count.omitted;
    if (count.note == 0) {
      count.note = items_.size();
      Diagnostic& note = items_.emplace_back();
      note.severity = Severity::Note;
      note.file = file.path;
      note.message = "too many problems in this file; the rest are not shown";
      note.notes.emplace_back();
    }
    items_[count.note].notes.back() = "and " + std::to_string(count.omitted) + " more";
    discarded_ = Diagnostic{};
    return discarded_;
  }
  ++count.kept;
  Diagnostic& d = items_.emplace_back();
  d.file = file.path;
  d.location = at;
  const std::string_view line = file.lineText(at.line);
  const std::size_t column = at.column > 0 ? at.column - 1 : 0;  // 0-based byte in `line`
  if (line.size() <= kMaxShownLineBytes) {
    d.sourceLine = std::string(line);
    d.caretColumn = at.column;
  } else {
    std::size_t begin = column > kMaxShownLineBytes / 2 ? column - kMaxShownLineBytes / 2 : 0;
    std::size_t end = std::min(line.size(), begin + kMaxShownLineBytes);
    while (begin > 0 && isContinuationByte(line[begin]))
      --begin;
    while (end < line.size() && isContinuationByte(line[end]))
      ++end;
    const std::string_view before = begin > 0 ? "..." : "";
    d.sourceLine = std::string(before) + std::string(line.substr(begin, end - begin)) +
                   (end < line.size() ? "..." : "");
    d.caretColumn = static_cast<std::uint32_t>(before.size() + column - begin + 1);
  }
  d.severity = severity;
  d.message = shortened(std::move(message), kMaxMessageBytes);
  return d;
}

bool Diagnostics::keeps(const SourceFile& file) const {
  const auto found = perFile_.find(file.path);
  return found == perFile_.end() || found->second.kept < kMaxKeptPerFile;
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
  for (const auto& [file, count] : other.perFile_) {
    FileCount& mine = perFile_[file];
    mine.kept += count.kept;
    mine.omitted += count.omitted;
  }
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
    const std::uint32_t column = d.caretColumn > 0 ? d.caretColumn : d.location.column;
    for (std::uint32_t i = 1; i < column && i - 1 < d.sourceLine.size(); ++i) {
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
