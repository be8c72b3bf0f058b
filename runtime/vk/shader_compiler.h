// GLSL → SPIR-V through glslang's library at start-up, with a disk cache of SPIR-V keyed by
// a hash of everything that decides the output (sources, defines, stage, target), so a
// second run with the same scene starts without compiling.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace memograph::runtime {

enum class ShaderStage { Compute, RayGen, ClosestHit, Miss, Callable };

struct ShaderCompileRequest {
  std::string entryFile;  // name in `files` of the file to compile
  ShaderStage stage = ShaderStage::Compute;
  std::vector<std::string> defines;  // "NAME" or "NAME=VALUE"
};

struct ShaderCacheStats {
  std::uint32_t hits = 0;
  std::uint32_t compiled = 0;
  double compileMilliseconds = 0.0;
};

// One compiler is used by one thread at a time (its statistics are not shared); several
// compilers may compile at once on different threads (glslang is initialised once, then
// thread-safe).
class ShaderCompiler {
 public:
  // `files`: every file an #include may name (embedded shaders plus generated ones).
  // `cacheDirectory`: empty disables the disk cache.
  ShaderCompiler(std::map<std::string, std::string> files, std::filesystem::path cacheDirectory);

  // Returns SPIR-V; throws std::runtime_error with glslang's log on a compile error.
  std::vector<std::uint32_t> compile(const ShaderCompileRequest& request);

  // Every request's SPIR-V, in the order given, compiled on up to `threads` threads (0: one
  // per hardware thread), each with a copy of this compiler. Adds their hits and compiles to
  // this compiler's statistics, and the wall time waited when anything was compiled (not
  // the threads' sum). Throws the first compile error.
  std::vector<std::vector<std::uint32_t>> compileAll(
      const std::vector<ShaderCompileRequest>& requests, std::uint32_t threads);

  const ShaderCacheStats& stats() const { return stats_; }

  // Adds the statistics of compilers that ran at the same time, each from the same start (a
  // fresh() copy per thread): their hits and compiles, and the longest of their compile
  // times, which is the wall time they took together.
  void addConcurrentStats(const std::vector<ShaderCacheStats>& concurrent);

  // A compiler of the same files and cache folder with fresh statistics, for another thread.
  ShaderCompiler fresh() const { return ShaderCompiler(files_, cacheDirectory_); }

  // A compiler that sees this one's files plus `name` (replacing one of that name): one
  // generated include per shader, as the per-material shaders need, with fresh statistics.
  ShaderCompiler withFile(const std::string& name, std::string text) const;

 private:
  std::map<std::string, std::string> files_;
  std::filesystem::path cacheDirectory_;
  ShaderCacheStats stats_;
};

// $XDG_CACHE_HOME/memograph/shaders, else ~/.cache/memograph/shaders, else empty.
std::filesystem::path defaultShaderCacheDirectory();

}  // namespace memograph::runtime
