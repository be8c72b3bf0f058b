#include "cli_common.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "compiler/input_file.h"
#include "runtime/host/atomic_file.h"

namespace memograph::cli {

namespace fs = std::filesystem;

int usageError(std::string_view command, std::string_view message) {
  std::cerr << "memograph " << command << ": " << message << "\n"
            << "Run 'memograph " << command << " --help' for usage.\n";
  return kExitUsage;
}

bool parseNumber(std::string_view text, std::uint32_t& out) {
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
  return error == std::errc() && end == text.data() + text.size();
}

bool parseReal(std::string_view text, double& out) {
  double value = 0.0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return false;
  out = value;
  return true;
}

bool parseImageSize(std::string_view text, std::uint32_t& width, std::uint32_t& height,
                    std::string& error) {
  const auto x = text.find('x');
  if (x == std::string_view::npos || !parseNumber(text.substr(0, x), width) ||
      !parseNumber(text.substr(x + 1), height)) {
    error = "expected WxH, e.g. 1920x1080, not '" + std::string(text) + "'";
    return false;
  }
  // Appended, not "'" + std::string(text): GCC 12 warns (-Wrestrict) on that falsely.
  std::string quoted = "'";
  quoted.append(text).append("'");
  if (width == 0 || height == 0 || width > kMaxImageSide || height > kMaxImageSide) {
    error = quoted + ": each side must be 1 to " + std::to_string(kMaxImageSide) + " pixels";
    return false;
  }
  if (std::uint64_t(width) * height > files::kMaxImagePixels) {
    error = quoted + " is over the limit of " + std::to_string(files::kMaxImagePixels) + " pixels";
    return false;
  }
  return true;
}

std::optional<int> ArgumentScanner::scan(std::vector<std::string>& positional) {
  bool onlyPositional = false, helpAsked = false;
  for (std::size_t i = 0; i < args_.size(); ++i) {
    const std::string_view arg = args_[i];
    if (onlyPositional || arg.size() < 2 || arg[0] != '-') {
      positional.emplace_back(arg);
      continue;
    }
    if (arg == "--") {
      onlyPositional = true;
      continue;
    }
    if (help_ && (arg == "--help" || arg == "-h")) {
      helpAsked = true;
      continue;
    }
    const auto equals = arg.find('=');
    const std::string_view name = arg.substr(0, equals);
    const auto found = std::find_if(options_.begin(), options_.end(),
                                    [&](const Option& o) { return o.name == name; });
    if (found == options_.end()) {
      return usageError(command_, "unknown option '" + std::string(name) + "'");
    }
    given_.push_back(found->name);
    if (found->flag) {
      if (equals != std::string_view::npos) {
        return usageError(command_, "option '" + std::string(name) + "' takes no value");
      }
      *found->flag = true;
      continue;
    }
    std::string_view value;
    if (equals != std::string_view::npos)
      value = arg.substr(equals + 1);
    else if (i + 1 < args_.size())
      value = args_[++i];
    // An empty value is no value: options whose default lives in the library (the culling
    // numbers) read "empty" as "not given", so `--low-frames ""` must not pass as it.
    if (value.empty() || (found->list && equals == std::string_view::npos && value[0] == '-'))
      return usageError(command_, "option '" + std::string(name) + "' needs a value");
    if (!found->list) {
      *found->value = std::string(value);
      continue;
    }
    found->list->emplace_back(value);
    if (equals != std::string_view::npos)
      continue;
    while (i + 1 < args_.size() && !args_[i + 1].empty() && args_[i + 1][0] != '-')
      found->list->emplace_back(args_[++i]);
  }
  if (helpAsked) {
    std::cout << *help_;
    return kExitOk;
  }
  return std::nullopt;
}

bool ArgumentScanner::given(std::string_view name) const {
  return std::find(given_.begin(), given_.end(), name) != given_.end();
}

std::string ignoredOptionNote(std::string_view option, std::string_view needs) {
  std::string note(option);
  return note.append(" is ignored: it needs ").append(needs);
}

std::optional<std::string> readFile(const std::string& path, std::string& error) {
  // Regular files up to the text limit only: a FIFO, /dev/zero or a huge file is refused
  // before reading (docs/guide/limits.md).
  return files::readInputFile(path, files::kMaxTextFileBytes, "graphs", error);
}

bool writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files,
                          std::string& error) {
  return files::writeFileSet(files, error);
}

int checkOutputFile(std::string_view command, const std::string& path) {
  std::string error;
  if (files::checkOutputPath(path, error))
    return kExitOk;
  std::cerr << "memograph " << command << ": " << path << ": " << error << "\n";
  return kExitFailure;
}

void printDiagnostics(const compiler::Diagnostics& diagnostics) {
  std::cerr << compiler::formatDiagnostics(diagnostics);
}

}  // namespace memograph::cli
