// A private folder for the fuzz targets whose code under test opens files by name (assimp,
// the staged-export check): each input is written there as the files it stands for.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

namespace memograph::fuzz {

// Makes <temp>/memograph-<name>-fuzz-XXXXXX, removed when the process exits; called once,
// from LLVMFuzzerInitialize. Aborts when the folder cannot be made: the target would test
// nothing.
inline std::string makePrivateFolder(const std::string& name) {
  static std::string folder;  // for the exit handler, which takes no argument
  std::string pattern =
      std::filesystem::temp_directory_path() / ("memograph-" + name + "-fuzz-XXXXXX");
  if (!::mkdtemp(pattern.data())) {
    std::perror("mkdtemp");
    std::abort();
  }
  folder = pattern;
  std::atexit([] {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  });
  return folder;
}

// `bytes` as the whole of the file at `path`; false when they could not all be written.
inline bool writeFile(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  return bool(out);
}

}  // namespace memograph::fuzz
