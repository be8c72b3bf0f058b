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

#ifdef MEMOGRAPH_HAVE_RUNTIME
#include "runtime/vk/vulkan_context.h"
#endif

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

void addFolderInputs(std::vector<CommandFile>& inputs, std::string_view role,
                     const std::string& folder, std::string_view extension, bool recursive) {
  if (folder.empty())
    return;
  std::error_code ec;
  std::size_t listed = 0;
  const auto add = [&](const fs::directory_entry& entry) {
    std::error_code typeError;
    if (entry.path().extension() == extension && entry.is_regular_file(typeError))
      inputs.push_back({std::string(role), entry.path().string()});
  };
  // Errors end the listing quietly: reading the folder later reports them with context.
  if (recursive) {
    for (fs::recursive_directory_iterator
             it(folder, fs::directory_options::skip_permission_denied, ec),
         end;
         !ec && it != end && listed < kMaxFolderInputs; it.increment(ec), ++listed)
      add(*it);
  } else {
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end && listed < kMaxFolderInputs;
         it.increment(ec), ++listed)
      add(*it);
  }
}

namespace {

// Whether `a` and `b` name one file. Both existing: the same device and inode
// (fs::equivalent follows links). Otherwise the paths with links, '.' and '..' resolved as
// far as they exist: an output not yet written can still be the same as another output.
bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  const bool aExists = fs::exists(a, ec), bExists = fs::exists(b, ec);
  if (aExists && bExists)
    return fs::equivalent(a, b, ec) && !ec;
  if (aExists != bExists)
    return false;
  // Made absolute first: weakly_canonical leaves a relative path whose first part does not
  // exist ("x.pfm") relative, so it would differ from "./x.pfm".
  const fs::path canonicalA = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec)
    return false;
  const fs::path canonicalB = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && canonicalA == canonicalB;
}

}  // namespace

int refuseOutputOverInput(std::string_view command, const std::vector<CommandFile>& outputs,
                          const std::vector<CommandFile>& inputs) {
  const auto refuse = [&](const CommandFile& output, const CommandFile& other,
                          std::string_view why) {
    return usageError(command, output.role + " '" + output.path + "' is " + other.role + " '" +
                                   other.path + "'" + std::string(why));
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const CommandFile& output = outputs[i];
    if (output.path.empty())
      continue;
    for (const CommandFile& input : inputs) {
      if (!input.path.empty() && sameFile(output.path, input.path))
        return refuse(output, input, ", an input: writing it would destroy what is read");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].path.empty() && sameFile(output.path, outputs[j].path))
        return refuse(output, outputs[j], ": two outputs cannot share a file");
    }
  }
  return kExitOk;
}

int checkDeviceIndex(std::string_view command, int deviceIndex) {
#ifdef MEMOGRAPH_HAVE_RUNTIME
  if (deviceIndex < 0)
    return kExitOk;
  std::vector<std::string> devices;
  try {
    devices = runtime::describeDevices();
  } catch (const std::exception&) {
    return kExitOk;  // no Vulkan loader or instance: the renderer reports it with the fix
  }
  if (devices.empty() || std::size_t(deviceIndex) < devices.size())
    return kExitOk;
  std::string message =
      "--device " + std::to_string(deviceIndex) + " is out of range: this machine has ";
  message += devices.size() == 1
                 ? "one Vulkan device, --device 0:"
                 : std::to_string(devices.size()) + " Vulkan devices, --device 0 to " +
                       std::to_string(devices.size() - 1) + ":";
  for (const std::string& device : devices)
    message.append("\n  ").append(device);
  return usageError(command, message);
#else
  (void)command;
  (void)deviceIndex;
  return kExitOk;
#endif
}

void printDiagnostics(const compiler::Diagnostics& diagnostics) {
  std::cerr << compiler::formatDiagnostics(diagnostics);
}

}  // namespace memograph::cli
