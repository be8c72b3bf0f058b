#include "runtime/host/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <signal.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

namespace memograph::files {

namespace fs = std::filesystem;

namespace {

// mkstemp creates files 0600; outputs get what open(2) would have given them.
mode_t creationMode() {
  static mode_t mode = [] {
    const mode_t mask = ::umask(022);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

fs::path folderOf(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

constexpr std::string_view kTemporaryMark = ".partial-";

// This host's mark in a temporary's name: 8 hex digits of a hash (FNV-1a) of its host
// name. A pid means something only on the host that wrote it: in a folder on shared storage
// (a render farm's frames), a writer on one node would otherwise take another node's live
// writer for a dead one and remove its temporary mid-write.
const std::string& hostMark() {
  static const std::string mark = [] {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0)
      name[0] = '\0';
    std::uint32_t hash = 2166136261u;
    for (const char* c = name; *c; ++c)
      hash = (hash ^ static_cast<unsigned char>(*c)) * 16777619u;
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", hash);
    return std::string(hex);
  }();
  return mark;
}

// The writer of a temporary: its pid, and its host's mark where the name has one (names
// without one, from before the mark, are taken as this host's).
struct TemporaryWriter {
  pid_t pid = 0;
  std::string host;
};

// The writer when `name` is one of our temporaries, `.<stem>.partial-<pid>[@<host>]-XXXXXX`
// then the target's extension (none, or one '.' and no other). A previous version kept
// aside during a commit (the same name + ".old") is not one: with a file system without
// hard links it may be the only copy of the user's file.
std::optional<TemporaryWriter> temporaryWriter(std::string_view name) {
  if (name.size() < 2 || name[0] != '.')
    return std::nullopt;
  const std::size_t mark = name.rfind(kTemporaryMark);
  if (mark == std::string_view::npos || mark == 0)
    return std::nullopt;
  std::string_view rest = name.substr(mark + kTemporaryMark.size());
  TemporaryWriter writer;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), writer.pid);
  if (ec != std::errc() || end == rest.data() || writer.pid <= 0)
    return std::nullopt;
  rest.remove_prefix(std::size_t(end - rest.data()));
  if (!rest.empty() && rest[0] == '@') {
    if (rest.size() < 9 || !std::all_of(rest.begin() + 1, rest.begin() + 9, [](char c) {
          return std::isxdigit(static_cast<unsigned char>(c));
        }))
      return std::nullopt;
    writer.host = rest.substr(1, 8);
    rest.remove_prefix(9);
  }
  if (rest.size() < 7 || rest[0] != '-')
    return std::nullopt;
  for (const char c : rest.substr(1, 6)) {
    if (!std::isalnum(static_cast<unsigned char>(c)))
      return std::nullopt;
  }
  // ".old" alone is skipped too: a backup of an extension-less target looks the same.
  const std::string_view extension = rest.substr(7);
  if (!extension.empty() && (extension[0] != '.' || extension == ".old" ||
                             extension.find('.', 1) != std::string_view::npos))
    return std::nullopt;
  return writer;
}

// Removes, once per folder and process, the temporaries in `folder` that processes which
// no longer exist left behind (killed mid-write: a bake's full-size images). Only regular
// files of our naming, owned by us, whose pid is not alive (kill(pid, 0) says ESRCH; a
// reused pid only keeps a temporary a while longer). The set of swept folders is
// process-wide so that a command writing many files into one folder lists it once.
void removeStaleTemporaries(const fs::path& folder) {
  static std::mutex mutex;
  static std::set<std::string> swept;
  {
    std::error_code ec;
    const std::string key = fs::weakly_canonical(folder, ec).string();
    const std::lock_guard lock(mutex);
    if (!swept.insert(ec ? folder.string() : key).second)
      return;
  }
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    const auto writer = temporaryWriter(name);
    if (!writer || writer->pid == ::getpid() ||
        (!writer->host.empty() && writer->host != hostMark()))
      continue;
    struct stat info {};
    if (::lstat(entry.path().c_str(), &info) != 0 || !S_ISREG(info.st_mode) ||
        info.st_uid != ::geteuid())
      continue;
    if (::kill(writer->pid, 0) == 0 || errno != ESRCH)
      continue;
    ::unlink(entry.path().c_str());
  }
}

// Holds exclusive flock(2)s on folders, released when destroyed. A folder is known by its
// device and inode, not its spelling: "out" and "./out" (or a link to it) are locked once,
// as a second flock on another descriptor of a locked folder would wait forever; and the
// locks are taken in that order, so two sets never deadlock however they spell a folder.
class FolderLocks {
 public:
  ~FolderLocks() {
    for (int fd : fds_)
      ::close(fd);  // closing releases the lock
  }
  bool lock(const std::set<std::string>& folders, std::string& error) {
    struct Opened {
      dev_t device;
      ino_t inode;
      int fd;
      std::string folder;
    };
    std::vector<Opened> opened;
    for (const auto& folder : folders) {
      const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd < 0) {
        error = errnoMessage(folder + ": cannot open the folder", errno);
        return false;
      }
      fds_.push_back(fd);
      struct stat info {};
      if (::fstat(fd, &info) != 0) {
        error = errnoMessage(folder + ": cannot read the folder", errno);
        return false;
      }
      opened.push_back({info.st_dev, info.st_ino, fd, folder});
    }
    std::sort(opened.begin(), opened.end(), [](const Opened& a, const Opened& b) {
      return std::pair(a.device, a.inode) < std::pair(b.device, b.inode);
    });
    for (std::size_t i = 0; i < opened.size(); ++i) {
      if (i > 0 && opened[i].device == opened[i - 1].device &&
          opened[i].inode == opened[i - 1].inode)
        continue;  // the same folder, spelled otherwise: locked already
      int result;
      do {
        result = ::flock(opened[i].fd, LOCK_EX);
      } while (result != 0 && errno == EINTR);
      // Some file systems have no flock: the set is still all-or-nothing for this process.
      if (result != 0 && errno != ENOLCK && errno != EOPNOTSUPP) {
        error = errnoMessage(opened[i].folder + ": cannot lock the folder", errno);
        return false;
      }
    }
    return true;
  }

 private:
  std::vector<int> fds_;
};

}  // namespace

std::string errnoMessage(std::string_view what, int errnoValue) {
  std::string message(what);
  message += ": ";
  message += errnoValue != 0 ? std::strerror(errnoValue) : "unknown error";
  return message;
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : target_(std::move(other.target_)),
      temporary_(std::move(other.temporary_)),
      fd_(other.fd_),
      committed_(other.committed_) {
  other.fd_ = -1;
  other.temporary_.clear();
}

StagedFile& StagedFile::operator=(StagedFile&& other) noexcept {
  if (this != &other) {
    discard();
    target_ = std::move(other.target_);
    temporary_ = std::move(other.temporary_);
    fd_ = other.fd_;
    committed_ = other.committed_;
    other.fd_ = -1;
    other.temporary_.clear();
  }
  return *this;
}

StagedFile::~StagedFile() {
  discard();
}

void StagedFile::discard() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (!committed_ && !temporary_.empty())
    ::unlink(temporary_.c_str());
  temporary_.clear();
}

bool StagedFile::create(const fs::path& target, std::string& error) {
  discard();
  committed_ = false;
  target_ = target;
  removeStaleTemporaries(folderOf(target));
  // ".<name>.partial-<pid>@<host>-XXXXXX<ext>": hidden, unique (mkstemps), the writer's
  // pid and host for removeStaleTemporaries, and the target's extension.
  const std::string extension = target.extension().string();
  std::string name = folderOf(target).string();  // appended, not operator+: GCC 12 bug 105329
  name += "/.";
  name += target.stem().string();
  name += kTemporaryMark;
  name += std::to_string(::getpid());
  name += '@';
  name += hostMark();
  name += "-XXXXXX";
  name += extension;
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkostemps(buffer.data(), static_cast<int>(extension.size()), O_CLOEXEC);
  if (fd < 0) {
    error = errnoMessage("cannot create a temporary file in " + folderOf(target).string(), errno);
    return false;
  }
  fd_ = fd;
  temporary_ = buffer.data();
  if (::fchmod(fd_, creationMode()) != 0) {
    error = errnoMessage("cannot set the file's permissions", errno);
    discard();
    return false;
  }
  return true;
}

bool StagedFile::write(std::string_view bytes, std::string& error) {
  if (fd_ < 0) {
    error = "internal: write before create";
    return false;
  }
  return writeAll(bytes, error) && sync(error);
}

bool StagedFile::writeAll(std::string_view bytes, std::string& error) {
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, data, left);
    if (written < 0) {
      if (errno == EINTR)
        continue;
      error = errnoMessage("cannot write", errno);
      return false;
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  return true;
}

bool StagedFile::sync(std::string& error) {
  int fd = fd_;
  bool own = false;
  if (fd < 0) {
    fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
    own = true;
    if (fd < 0) {
      error = errnoMessage("the written file is missing", errno);
      return false;
    }
  }
  const int result = ::fsync(fd);
  const int saved = errno;
  if (own)
    ::close(fd);
  if (result != 0 && saved != EINVAL) {  // EINVAL: a file system without fsync
    error = errnoMessage("cannot write", saved);
    return false;
  }
  return true;
}

bool StagedFile::adopt(const fs::path& written, std::string& error) {
  if (temporary_.empty()) {
    error = "internal: adopt before create";
    return false;
  }
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (::rename(written.c_str(), temporary_.c_str()) == 0)
    return sync(error);
  if (errno != EXDEV) {
    error = errnoMessage("cannot move " + written.string(), errno);
    return false;
  }
  // Another file system: copied into the temporary (still unique, still ours).
  const int in = ::open(written.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) {
    error = errnoMessage("cannot read " + written.string(), errno);
    return false;
  }
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd_ < 0) {
    error = errnoMessage("cannot reopen the temporary file", errno);
    ::close(in);
    return false;
  }
  std::vector<char> buffer(1 << 16);
  for (;;) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0) {
      error = errnoMessage("cannot read " + written.string(), errno);
      ::close(in);
      return false;
    }
    if (n == 0)
      break;
    std::string cause;
    if (!writeAll(std::string_view(buffer.data(), std::size_t(n)), cause)) {
      error = cause;
      ::close(in);
      return false;
    }
  }
  ::close(in);
  return sync(error);
}

bool StagedFile::commit(std::string& error) {
  if (temporary_.empty()) {
    error = "internal: commit without a staged file";
    return false;
  }
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    error = errnoMessage("cannot replace the file", errno);
    return false;
  }
  committed_ = true;
  temporary_.clear();
  return true;
}

bool writeFileAtomically(const fs::path& path, std::string_view bytes, std::string& error) {
  StagedFile file;
  return file.create(path, error) && file.write(bytes, error) && file.commit(error);
}

bool writeFileAtomicallyWith(
    const fs::path& path,
    const std::function<bool(const fs::path& temporary, std::string& error)>& writeTo,
    std::string& error) {
  StagedFile file;
  return file.create(path, error) && writeTo(file.temporaryPath(), error) && file.sync(error) &&
         file.commit(error);
}

bool writeFileSet(const std::vector<std::pair<std::string, std::string>>& files,
                  std::string& error) {
  // Stage everything first: a full disk or a bad folder fails here, with nothing replaced.
  std::vector<StagedFile> staged(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::string cause;
    if (!staged[i].create(files[i].first, cause) || !staged[i].write(files[i].second, cause)) {
      error = files[i].first + ": " + cause;
      return false;
    }
  }
  return commitFileSet(staged, error);
}

bool commitFileSet(std::vector<StagedFile>& staged, std::string& error) {
  std::set<std::string> folders;
  for (const auto& file : staged)
    folders.insert(folderOf(file.target()).string());
  FolderLocks locks;
  if (!locks.lock(folders, error))
    return false;

  // Each replaced file's previous version is kept aside as a hard link next to it (the
  // temporary's unique name + ".old"), so the target never disappears and can be restored.
  struct Done {
    std::string target;
    std::string backup;  // empty: the file is new
  };
  std::vector<Done> done;
  auto rollBack = [&] {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      if (it->backup.empty())
        ::unlink(it->target.c_str());
      else
        ::rename(it->backup.c_str(), it->target.c_str());
    }
  };
  for (std::size_t i = 0; i < staged.size(); ++i) {
    const std::string target = staged[i].target().string();
    std::string backup = staged[i].temporaryPath().string() + ".old";
    bool movedAside = false;
    struct stat existing {};
    if (::lstat(target.c_str(), &existing) != 0) {
      backup.clear();  // a new file: rolling back removes it
    } else if (S_ISDIR(existing.st_mode)) {
      // Never moved aside or replaced: a folder where a file should go is an error.
      error = target + ": cannot replace the file: it is a folder";
      rollBack();
      return false;
    } else if (::link(target.c_str(), backup.c_str()) != 0) {
      // Without hard links (EPERM on some file systems) the old version is moved aside
      // instead: still restorable, at the cost of a moment without the target.
      if (::rename(target.c_str(), backup.c_str()) != 0) {
        error = errnoMessage(target + ": cannot keep the previous version", errno);
        rollBack();
        return false;
      }
      movedAside = true;
    }
    std::string cause;
    if (!staged[i].commit(cause)) {
      error = target + ": " + cause;
      if (movedAside)
        ::rename(backup.c_str(), target.c_str());  // put the old version back
      else if (!backup.empty())
        ::unlink(backup.c_str());  // a second link: the target itself is untouched
      rollBack();
      return false;
    }
    done.push_back({target, std::move(backup)});
  }
  for (const auto& d : done) {
    if (!d.backup.empty())
      ::unlink(d.backup.c_str());
  }
  return true;
}

bool checkOutputPath(const fs::path& path, std::string& error) {
  if (path.empty()) {
    error = "the output path is empty";
    return false;
  }
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) {
      error = "is a folder; name a file to write";
      return false;
    }
  } else if (errno != ENOENT) {
    error = errnoMessage("cannot use as an output", errno);
    return false;
  }
  // Quoted by appending, not operator+: GCC 12 bug 105329 warns on the latter.
  const fs::path folder = folderOf(path);
  std::string quoted = "'";
  quoted += folder.string();
  quoted += "'";
  if (::stat(folder.c_str(), &info) != 0) {
    const int cause = errno;
    error = cause == ENOENT ? "the folder " + quoted + " does not exist"
                            : errnoMessage("cannot write into folder " + quoted, cause);
    return false;
  }
  if (!S_ISDIR(info.st_mode)) {
    error = quoted + " is not a folder";
    return false;
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    error = errnoMessage("cannot write into folder " + quoted, errno);
    return false;
  }
  return true;
}

}  // namespace memograph::files
