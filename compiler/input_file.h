// Reading input files with bounds (docs/guide/limits.md): only regular files (a FIFO
// would block forever, /dev/zero never ends), no larger than a documented limit, checked
// before anything is allocated, and file-system errors (symlink loops, over-long names)
// turned into messages instead of exceptions. C++ standard library only, like the rest
// of the compiler, so every layer above can use it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace memograph::files {

// The limits of docs/guide/limits.md.
inline constexpr std::uint64_t kMiB = 1024 * 1024;
// Text inputs: material graphs, node library files, camera paths.
inline constexpr std::uint64_t kMaxTextFileBytes = 16 * kMiB;
// Scene files (glTF, glb, OBJ and their buffers) and images (textures, environments, diff).
inline constexpr std::uint64_t kMaxSceneFileBytes = 1024 * kMiB;
inline constexpr std::uint64_t kMaxImageFileBytes = 1024 * kMiB;
// Pixels of an image read by us (width × height), e.g. 16384 × 8192: 2 GiB as float RGBA.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 27;

// Checks that `path` names a regular file of at most `maxBytes` bytes and returns its
// size; otherwise nullopt and `error` says why, without the path ("no such file",
// "a symbolic link loop", "the name is too long", "not a regular file (a FIFO)",
// "the file is 2.0 GiB, over the limit of 16 MiB for graphs"). `what` names the kind of
// input in the limit message ("graphs", "images").
std::optional<std::uint64_t> checkInputFile(const std::filesystem::path& path,
                                            std::uint64_t maxBytes, const std::string& what,
                                            std::string& error);

// checkInputFile, then the whole file as bytes.
std::optional<std::string> readInputFile(const std::filesystem::path& path, std::uint64_t maxBytes,
                                         const std::string& what, std::string& error);

// A file-system error as a short phrase: "no such file", "a symbolic link loop", ….
std::string describeFileError(const std::error_code& ec);

// "16 MiB", "1 GiB", "512 bytes".
std::string formatBytes(std::uint64_t bytes);

}  // namespace memograph::files
