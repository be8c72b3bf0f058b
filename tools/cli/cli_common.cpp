#include "cli_common.h"

#include <unistd.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

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

int ArgumentScanner::scan(std::vector<std::string>& positional) {
  bool onlyPositional = false;
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
    const auto equals = arg.find('=');
    const std::string_view name = arg.substr(0, equals);
    const auto found = std::find_if(options_.begin(), options_.end(),
                                    [&](const Option& o) { return o.name == name; });
    if (found == options_.end()) {
      return usageError(command_, "unknown option '" + std::string(name) + "'");
    }
    if (found->flag) {
      if (equals != std::string_view::npos) {
        return usageError(command_, "option '" + std::string(name) + "' takes no value");
      }
      *found->flag = true;
      continue;
    }
    if (equals != std::string_view::npos) {
      *found->value = std::string(arg.substr(equals + 1));
    } else if (i + 1 < args_.size()) {
      *found->value = std::string(args_[++i]);
    } else {
      return usageError(command_, "option '" + std::string(name) + "' needs a value");
    }
  }
  return kExitOk;
}

std::optional<std::string> readFile(const std::string& path, std::string& error) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = path + ": is a directory, not a file";
    return std::nullopt;
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    error = path + ": cannot open (" +
            (fs::exists(path, ec) ? "permission denied" : "no such file") + ")";
    return std::nullopt;
  }
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) {
    error = path + ": read failed";
    return std::nullopt;
  }
  return text.str();
}

bool writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files,
                          std::string& error) {
  std::vector<std::string> temporaries;
  auto cleanUp = [&] {
    std::error_code ignored;
    for (const auto& t : temporaries)
      fs::remove(t, ignored);
  };
  for (const auto& [path, contents] : files) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
    if (stream)
      temporaries.push_back(temporary);
    stream << contents;
    stream.close();
    if (!stream) {
      error = path + ": cannot write";
      cleanUp();
      return false;
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    fs::rename(temporaries[i], files[i].first, ec);
    if (ec) {
      error = files[i].first + ": cannot write (" + ec.message() + ")";
      cleanUp();
      return false;
    }
  }
  return true;
}

void printDiagnostics(const compiler::Diagnostics& diagnostics) {
  std::cerr << compiler::formatDiagnostics(diagnostics);
}

}  // namespace memograph::cli
