#include "compiler/input_file.h"

#include <cerrno>
#include <fstream>
#include <system_error>

namespace memograph::files {

namespace fs = std::filesystem;

std::string describeFileError(const std::error_code& ec) {
  switch (ec.value()) {
    case ENOENT:
      return "no such file";
    case ELOOP:
      return "a symbolic link loop (too many levels of symbolic links)";
    case ENAMETOOLONG:
      return "the name is too long";
    case EACCES:
    case EPERM:
      return "permission denied";
    case ENOTDIR:
      return "a part of the path is not a folder";
    default:
      return ec.message();
  }
}

std::string formatBytes(std::uint64_t bytes) {
  if (bytes >= 1024 * kMiB && bytes % (1024 * kMiB) == 0)
    return std::to_string(bytes / (1024 * kMiB)) + " GiB";
  if (bytes >= kMiB && bytes % kMiB == 0)
    return std::to_string(bytes / kMiB) + " MiB";
  if (bytes >= kMiB)
    return std::to_string(bytes / kMiB) + "." + std::to_string(bytes % kMiB * 10 / kMiB) + " MiB";
  return std::to_string(bytes) + " bytes";
}

std::optional<std::uint64_t> checkInputFile(const fs::path& path, std::uint64_t maxBytes,
                                            const std::string& what, std::string& error) {
  if (path.empty()) {
    // Joined to a base folder, "" would name the folder and read as "is a folder".
    error = "the path is empty";
    return std::nullopt;
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    // fs::status reports a missing file as not_found with an error code set; a symlink
    // loop or an over-long name as its own errno, which must not read as "no such file".
    error = describeFileError(ec ? ec : std::make_error_code(std::errc::no_such_file_or_directory));
    return std::nullopt;
  }
  if (fs::is_directory(status)) {
    error = "is a folder, not a file";
    return std::nullopt;
  }
  if (!fs::is_regular_file(status)) {
    // Reading a FIFO blocks until a writer comes; a device such as /dev/zero never ends.
    const char* kind = fs::is_fifo(status)             ? "a FIFO"
                       : fs::is_character_file(status) ? "a character device"
                       : fs::is_block_file(status)     ? "a block device"
                       : fs::is_socket(status)         ? "a socket"
                                                       : "a special file";
    error = std::string("not a regular file (") + kind + "); only regular files are read";
    return std::nullopt;
  }
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) {
    error = describeFileError(ec);
    return std::nullopt;
  }
  if (size > maxBytes) {
    error = "the file is " + formatBytes(size) + ", over the limit of " + formatBytes(maxBytes) +
            " for " + what + " (docs/guide/limits.md)";
    return std::nullopt;
  }
  return size;
}

std::optional<std::string> readInputFile(const fs::path& path, std::uint64_t maxBytes,
                                         const std::string& what, std::string& error) {
  const auto size = checkInputFile(path, maxBytes, what, error);
  if (!size)
    return std::nullopt;
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    error = "cannot open the file";
    return std::nullopt;
  }
  // Read the size checked, no more: a file that grew after the check is refused, never
  // read without bound.
  std::string bytes;
  bytes.resize(static_cast<std::size_t>(*size));
  stream.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(stream.gcount()));
  if (stream.bad()) {
    error = "read failed";
    return std::nullopt;
  }
  if (bytes.size() == *size && stream.peek() != std::char_traits<char>::eof()) {
    error = "the file grew while being read";
    return std::nullopt;
  }
  return bytes;
}

}  // namespace memograph::files
