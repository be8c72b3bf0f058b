#include "runtime/vk/shader_compiler.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <stdexcept>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#include "runtime/host/atomic_file.h"
#include "runtime/host/parallel_for.h"

namespace memograph::runtime {

namespace {

// Bump when anything about how SPIR-V is produced changes without the sources changing.
constexpr const char* kCacheFormat = "memograph-spirv-2";  // 2: entries have a header

EShLanguage toGlslang(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Compute:
      return EShLangCompute;
    case ShaderStage::RayGen:
      return EShLangRayGen;
    case ShaderStage::ClosestHit:
      return EShLangClosestHit;
    case ShaderStage::Miss:
      return EShLangMiss;
    case ShaderStage::Callable:
      return EShLangCallable;
  }
  return EShLangCompute;
}

// glslang keeps process-wide tables; initialise them once and never tear them down while
// another thread might compile.
void initializeGlslangOnce() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// 64-bit FNV-1a, fed piece by piece with length prefixes so piece boundaries count.
class Hasher {
 public:
  void add(std::string_view text) {
    addRaw(std::to_string(text.size()) + ":");
    addRaw(text);
  }
  std::uint64_t value() const { return hash_; }

 private:
  void addRaw(std::string_view text) {
    for (unsigned char c : text) {
      hash_ ^= c;
      hash_ *= 1099511628211ull;
    }
  }
  std::uint64_t hash_ = 14695981039346656037ull;
};

class MapIncluder : public glslang::TShader::Includer {
 public:
  explicit MapIncluder(const std::map<std::string, std::string>& files) : files_(files) {}

  IncludeResult* includeLocal(const char* headerName, const char*, size_t) override {
    return find(headerName);
  }
  IncludeResult* includeSystem(const char* headerName, const char*, size_t) override {
    return find(headerName);
  }
  void releaseInclude(IncludeResult* result) override {
    std::unique_ptr<IncludeResult> owned(result);  // glslang hands ownership back here
  }

 private:
  IncludeResult* find(const char* name) {
    auto it = files_.find(name);
    if (it == files_.end())
      return nullptr;
    return std::make_unique<IncludeResult>(it->first, it->second.data(), it->second.size(), nullptr)
        .release();
  }
  const std::map<std::string, std::string>& files_;
};

// A cache entry: a header of kCacheHeaderWords words (magic, format, SPIR-V word count,
// 64-bit FNV-1a of the SPIR-V bytes as two words), then the SPIR-V. A truncated or corrupt
// entry (a full disk, a crash of an older version, a disk error) is found by the length and
// the checksum, dropped with a warning and recompiled, instead of reaching the driver
// (VK_ERROR_INVALID_SHADER_NV, -13, on every later run).
constexpr std::uint32_t kCacheMagic = 0x4353474du;  // "MGSC"
constexpr std::uint32_t kCacheVersion = 2;
constexpr std::size_t kCacheHeaderWords = 5;
constexpr std::uint32_t kSpirvMagic = 0x07230203u;
// No shader of ours comes near this; a larger file is not a cache entry of ours.
constexpr std::uintmax_t kMaxCacheEntryBytes = 64u << 20;

std::uint64_t checksum(const std::vector<std::uint32_t>& words, std::size_t first) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = first; i < words.size(); ++i) {
    for (int b = 0; b < 4; ++b) {
      hash ^= (words[i] >> (8 * b)) & 0xffu;
      hash *= 1099511628211ull;
    }
  }
  return hash;
}

// Why an entry is unusable, or empty when it is good.
std::string validateCache(const std::vector<std::uint32_t>& words) {
  if (words.size() <= kCacheHeaderWords)
    return "shorter than its header";
  if (words[0] != kCacheMagic || words[1] != kCacheVersion)
    return "not a memograph cache entry of this version";
  if (words[2] != words.size() - kCacheHeaderWords)
    return "truncated: " + std::to_string(words.size() - kCacheHeaderWords) + " of " +
           std::to_string(words[2]) + " SPIR-V words";
  const std::uint64_t sum = checksum(words, kCacheHeaderWords);
  if (words[3] != std::uint32_t(sum) || words[4] != std::uint32_t(sum >> 32))
    return "checksum mismatch";
  if (words[kCacheHeaderWords] != kSpirvMagic)
    return "no SPIR-V magic number";
  return {};
}

void dropCache(const std::filesystem::path& path, const std::string& why) {
  std::cerr << "memograph: warning: shader cache entry " << path.string() << " is corrupt (" << why
            << "); removed, the shader is compiled again\n";
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

std::vector<std::uint32_t> readCache(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    return {};  // not cached yet
  if (!std::filesystem::is_regular_file(status))
    return {};  // not ours to remove (a folder or a device someone put there)
  const auto size = std::filesystem::file_size(path, ec);
  if (ec)
    return {};
  if (size % 4 != 0 || size > kMaxCacheEntryBytes) {
    dropCache(path, size % 4 != 0 ? "its size is not a whole number of words" : "too large");
    return {};
  }
  std::vector<std::uint32_t> words(size / 4);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(words.data()), std::streamsize(size));
  if (!in)
    return {};  // unreadable now (a race with a writer's rename is impossible: renames are
                // atomic); compile without touching it
  if (const std::string why = validateCache(words); !why.empty()) {
    dropCache(path, why);
    return {};
  }
  return {words.begin() + kCacheHeaderWords, words.end()};
}

// The cache is an optimisation: an entry that cannot be written (a read-only or full disk,
// a file-size limit) is a warning, once per process, and the shader is used as compiled.
void warnCacheUnwritable(const std::filesystem::path& path, const std::string& why) {
  static std::atomic_flag warned = ATOMIC_FLAG_INIT;
  if (warned.test_and_set())
    return;
  std::cerr << "memograph: warning: cannot write the shader cache entry " << path.string() << " ("
            << why << "); shaders are compiled again on the next run\n";
}

void writeCache(const std::filesystem::path& path, const std::vector<std::uint32_t>& spirv) {
  std::error_code error;
  std::filesystem::create_directories(path.parent_path(), error);
  if (error) {
    warnCacheUnwritable(path, "cannot create its folder: " + error.message());
    return;
  }
  std::vector<std::uint32_t> words(kCacheHeaderWords);
  words.insert(words.end(), spirv.begin(), spirv.end());
  const std::uint64_t sum = checksum(words, kCacheHeaderWords);
  words[0] = kCacheMagic;
  words[1] = kCacheVersion;
  words[2] = std::uint32_t(spirv.size());
  words[3] = std::uint32_t(sum);
  words[4] = std::uint32_t(sum >> 32);
  // A unique temporary, fsynced, renamed (files::writeFileAtomically): readers see all or
  // nothing, and a failed write (a full disk) removes its temporary.
  std::string why;
  if (!files::writeFileAtomically(
          path, std::string_view(reinterpret_cast<const char*>(words.data()), words.size() * 4),
          why))
    warnCacheUnwritable(path, why);
}

}  // namespace

std::filesystem::path defaultShaderCacheDirectory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "memograph" / "shaders";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "memograph" / "shaders";
  return {};
}

ShaderCompiler::ShaderCompiler(std::map<std::string, std::string> files,
                               std::filesystem::path cacheDirectory)
    : files_(std::move(files)), cacheDirectory_(std::move(cacheDirectory)) {}

ShaderCompiler ShaderCompiler::withFile(const std::string& name, std::string text) const {
  std::map<std::string, std::string> files = files_;
  files[name] = std::move(text);
  return ShaderCompiler(std::move(files), cacheDirectory_);
}

std::vector<std::vector<std::uint32_t>> ShaderCompiler::compileAll(
    const std::vector<ShaderCompileRequest>& requests, std::uint32_t threads) {
  std::vector<std::vector<std::uint32_t>> spirv(requests.size());
  std::vector<ShaderCompiler> compilers(workerThreads(threads, requests.size()), fresh());
  const auto start = std::chrono::steady_clock::now();
  parallelFor(requests.size(), threads, [&](std::size_t index, std::uint32_t thread) {
    spirv[index] = compilers[thread].compile(requests[index]);
  });
  const double waited =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const auto& compiler : compilers) {
    stats_.hits += compiler.stats_.hits;
    stats_.compiled += compiler.stats_.compiled;
  }
  if (std::any_of(compilers.begin(), compilers.end(),
                  [](const ShaderCompiler& c) { return c.stats_.compiled > 0; }))
    stats_.compileMilliseconds += waited;
  return spirv;
}

void ShaderCompiler::addConcurrentStats(const std::vector<ShaderCacheStats>& concurrent) {
  double longest = 0.0;
  for (const auto& s : concurrent) {
    stats_.hits += s.hits;
    stats_.compiled += s.compiled;
    longest = std::max(longest, s.compileMilliseconds);
  }
  stats_.compileMilliseconds += longest;
}

std::vector<std::uint32_t> ShaderCompiler::compile(const ShaderCompileRequest& request) {
  auto entry = files_.find(request.entryFile);
  if (entry == files_.end())
    throw std::runtime_error("shader source not found: " + request.entryFile);

  std::string preamble;
  for (const auto& define : request.defines) {
    auto eq = define.find('=');
    preamble +=
        "#define " +
        (eq == std::string::npos ? define : define.substr(0, eq) + " " + define.substr(eq + 1)) +
        "\n";
  }

  // The key covers every file an include could reach, the defines, the stage, the target
  // and the compiler's version: the cached SPIR-V is valid exactly when all are equal.
  Hasher hasher;
  hasher.add(kCacheFormat);
  hasher.add(std::to_string(GLSLANG_VERSION_MAJOR) + "." + std::to_string(GLSLANG_VERSION_MINOR) +
             "." + std::to_string(GLSLANG_VERSION_PATCH));
  hasher.add("vulkan1.2/spirv1.4");
  hasher.add(std::to_string(static_cast<int>(request.stage)));
  hasher.add(request.entryFile);
  hasher.add(preamble);
  for (const auto& [name, text] : files_) {
    hasher.add(name);
    hasher.add(text);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hasher.value()));
  std::filesystem::path cachePath;
  if (!cacheDirectory_.empty()) {
    cachePath = cacheDirectory_ / (std::string(hex) + ".spv");
    auto cached = readCache(cachePath);
    if (!cached.empty()) {
      ++stats_.hits;
      return cached;
    }
  }

  auto start = std::chrono::steady_clock::now();
  initializeGlslangOnce();
  EShLanguage stage = toGlslang(request.stage);
  glslang::TShader shader(stage);
  const char* text = entry->second.c_str();
  int length = static_cast<int>(entry->second.size());
  const char* name = entry->first.c_str();
  shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_4);
  auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  MapIncluder includer(files_);
  if (!shader.parse(GetDefaultResources(), 460, false, messages, includer)) {
    throw std::runtime_error("GLSL compile error in " + request.entryFile + ":\n" +
                             shader.getInfoLog() + shader.getInfoDebugLog());
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    throw std::runtime_error("GLSL link error in " + request.entryFile + ":\n" +
                             program.getInfoLog());
  }
  std::vector<std::uint32_t> spirv;
  glslang::SpvOptions options;
  glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
  stats_.compileMilliseconds +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ++stats_.compiled;
  if (!cachePath.empty())
    writeCache(cachePath, spirv);
  return spirv;
}

}  // namespace memograph::runtime
