#include "tools/cli/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace memograph::cli {

namespace {

using Clock = std::chrono::steady_clock;

// The write end of the self-pipe the signal handler reports to. A handler can reach only
// global state; it is set only while a SignalPipe exists (one child at a time).
volatile sig_atomic_t gSignalPipe = -1;

extern "C" void reportSignal(int signal) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(signal);
  if (gSignalPipe >= 0) [[maybe_unused]]
    const ssize_t ignored = ::write(gSignalPipe, &byte, 1);
  errno = saved;
}

constexpr std::array<int, 3> kForwardedSignals = {SIGINT, SIGTERM, SIGHUP};

// SIGINT, SIGTERM and SIGHUP turned into bytes on a pipe that the wait loop polls, for as
// long as this lives; the previous handlers come back afterwards. A signal that was
// ignored when we started (a `nohup`, a background job's SIGINT) stays ignored.
class SignalPipe {
 public:
  SignalPipe() {
    if (::pipe2(fds_, O_CLOEXEC | O_NONBLOCK) != 0) {
      fds_[0] = fds_[1] = -1;
      return;
    }
    gSignalPipe = fds_[1];
    for (std::size_t i = 0; i < kForwardedSignals.size(); ++i) {
      struct sigaction action {};
      action.sa_handler = reportSignal;
      sigemptyset(&action.sa_mask);
      ::sigaction(kForwardedSignals[i], nullptr, &previous_[i]);
      if (previous_[i].sa_handler == SIG_IGN)
        continue;
      ::sigaction(kForwardedSignals[i], &action, nullptr);
    }
  }
  ~SignalPipe() {
    if (fds_[0] < 0)
      return;
    for (std::size_t i = 0; i < kForwardedSignals.size(); ++i)
      ::sigaction(kForwardedSignals[i], &previous_[i], nullptr);
    gSignalPipe = -1;
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  SignalPipe(const SignalPipe&) = delete;
  SignalPipe& operator=(const SignalPipe&) = delete;

  bool ok() const { return fds_[0] >= 0; }
  int readEnd() const { return fds_[0]; }
  // The first signal received, or 0.
  int received() const {
    unsigned char byte = 0;
    return ::read(fds_[0], &byte, 1) == 1 ? byte : 0;
  }

 private:
  int fds_[2] = {-1, -1};
  std::array<struct sigaction, kForwardedSignals.size()> previous_{};
};

// Splits the child's stdout into lines as it arrives. Each byte is looked at once (only the
// new bytes are searched for a newline), and at most maxLineBytes of a line and tailBytes
// of the tail are held, whatever the child prints.
class LineSplitter {
 public:
  explicit LineSplitter(const ChildOptions& options) : options_(options) {}

  void feed(std::string_view bytes) {
    keepTail(bytes);
    while (!bytes.empty()) {
      const std::size_t newline = bytes.find('\n');
      append(bytes.substr(0, newline));
      if (newline == std::string_view::npos)
        return;
      emit();
      bytes.remove_prefix(newline + 1);
    }
  }
  void finish() {
    if (!line_.empty() || cut_)
      emit();
  }
  std::string tail() const { return tail_; }

 private:
  void append(std::string_view part) {
    const std::size_t room = options_.maxLineBytes - std::min(options_.maxLineBytes, line_.size());
    if (part.size() > room)
      cut_ = true;
    line_.append(part.substr(0, room));
  }
  void emit() {
    if (options_.onLine)
      options_.onLine(line_, cut_);
    line_.clear();
    cut_ = false;
  }
  void keepTail(std::string_view bytes) {
    if (bytes.size() >= options_.tailBytes) {
      tail_.assign(bytes.substr(bytes.size() - options_.tailBytes));
      return;
    }
    tail_.append(bytes);
    if (tail_.size() > 2 * options_.tailBytes)  // trimmed now and then: amortized linear
      tail_.erase(0, tail_.size() - options_.tailBytes);
  }

  const ChildOptions& options_;
  std::string line_;
  bool cut_ = false;
  std::string tail_;
};

// Ends the group `group` (the child and whatever it started): SIGTERM, then SIGKILL to what
// is left after a grace period. The child itself is not reaped here.
void killGroup(pid_t group) {
  if (::kill(-group, SIGTERM) != 0)
    return;  // nothing left
  const auto deadline = Clock::now() + std::chrono::seconds(2);
  siginfo_t info{};
  while (Clock::now() < deadline) {
    info.si_pid = 0;
    // Polls the leader without reaping it: its pid (the group's id) stays taken until then.
    if (::waitid(P_PID, id_t(group), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid != 0)
      break;
    ::usleep(20 * 1000);
  }
  ::kill(-group, SIGKILL);
}

ChildResult reap(pid_t pid, ChildResult result) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (result.ending == ChildResult::Ending::Exited) {
    if (WIFSIGNALED(status)) {
      result.ending = ChildResult::Ending::Signalled;
      result.signal = WTERMSIG(status);
    } else {
      result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    }
  }
  return result;
}

}  // namespace

ChildResult runChild(const std::vector<std::string>& argv, const ChildOptions& options) {
  ChildResult result;
  std::vector<char*> cargv;
  for (const auto& s : argv)
    cargv.push_back(const_cast<char*>(s.c_str()));
  cargv.push_back(nullptr);

  SignalPipe signals;
  int out[2], failure[2];
  if (!signals.ok() || ::pipe2(out, O_CLOEXEC) != 0) {
    result.error = std::string("cannot make a pipe: ") + std::strerror(errno);
    return result;
  }
  if (::pipe2(failure, O_CLOEXEC) != 0) {
    result.error = std::string("cannot make a pipe: ") + std::strerror(errno);
    ::close(out[0]);
    ::close(out[1]);
    return result;
  }
  const int devNull = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls until exec. Its own group: a terminal's Ctrl-C reaches
    // only us, and we end the whole group, grandchildren included.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent)  // we died before prctl took effect
      ::_exit(127);
    if (devNull >= 0)
      ::dup2(devNull, STDIN_FILENO);
    ::dup2(out[1], STDOUT_FILENO);
    ::execv(cargv[0], cargv.data());
    const int cause = errno;
    [[maybe_unused]] const ssize_t ignored = ::write(failure[1], &cause, sizeof cause);
    ::_exit(127);
  }
  const int forkErrno = errno;
  if (devNull >= 0)
    ::close(devNull);
  ::close(out[1]);
  ::close(failure[1]);
  if (pid < 0) {
    result.error = std::string("cannot start a process: ") + std::strerror(forkErrno);
    ::close(out[0]);
    ::close(failure[0]);
    return result;
  }
  ::setpgid(pid, pid);  // also here: whichever runs first, the group exists before a kill
  int cause = 0;
  ssize_t got;
  while ((got = ::read(failure[0], &cause, sizeof cause)) < 0 && errno == EINTR) {
  }
  ::close(failure[0]);
  if (got == sizeof cause) {
    ::close(out[0]);
    result.error = std::string("cannot run ") + argv[0] + ": " + std::strerror(cause);
    reap(pid, result);
    return result;
  }

  result.ending = ChildResult::Ending::Exited;
  LineSplitter lines(options);
  std::vector<char> buffer(64 * 1024);
  const auto deadline = Clock::now() + options.timeout;
  bool outputOpen = true;
  while (true) {
    // The child may close its stdout and go on running: then its exit is polled for.
    siginfo_t info{};
    if (!outputOpen && ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid != 0)
      break;
    int waitMs = outputOpen ? 1000 : 50;
    if (options.timeout.count() > 0) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) {
        result.ending = ChildResult::Ending::TimedOut;
        break;
      }
      waitMs = int(std::min<long long>(waitMs, left));
    }
    std::array<pollfd, 2> fds = {pollfd{signals.readEnd(), POLLIN, 0},
                                 pollfd{outputOpen ? out[0] : -1, POLLIN, 0}};
    if (::poll(fds.data(), fds.size(), waitMs) < 0 && errno != EINTR)
      break;
    if (const int signal = signals.received()) {
      result.ending = ChildResult::Ending::Interrupted;
      result.signal = signal;
      break;
    }
    if (outputOpen && (fds[1].revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t n = ::read(out[0], buffer.data(), buffer.size());
      if (n > 0)
        lines.feed(std::string_view(buffer.data(), std::size_t(n)));
      else if (n == 0 || errno != EINTR)
        outputOpen = false;
    }
  }
  ::close(out[0]);
  lines.finish();
  result.tail = lines.tail();
  // Whatever the child left in its group goes with it, before the leader is reaped (so its
  // pid, the group's id, cannot be reused meanwhile).
  killGroup(pid);
  return reap(pid, std::move(result));
}

}  // namespace memograph::cli
