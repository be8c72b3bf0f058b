// Runs a helper program (Blender, for `import-blender`) that the CLI does not trust to end
// or to behave: in its own process group, with a time limit, its stdout read line by line
// in linear time with bounded memory, and SIGINT, SIGTERM and SIGHUP sent to us ending the
// whole group instead of leaving it running. The child also dies with us on SIGKILL
// (PR_SET_PDEATHSIG), which nothing can catch.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace memograph::cli {

struct ChildOptions {
  std::chrono::milliseconds timeout{0};  // 0: no limit
  // Called for each line of the child's stdout, without the newline. A line longer than
  // maxLineBytes is cut there (`cut` true) and the rest of it dropped.
  std::function<void(std::string_view line, bool cut)> onLine;
  std::size_t maxLineBytes = 64 * 1024;
  // How much of the end of the child's stdout is kept for an error message.
  std::size_t tailBytes = 4 * 1024;
};

struct ChildResult {
  enum class Ending {
    Exited,       // exitCode is its status
    Signalled,    // the child died of `signal`
    TimedOut,     // past the timeout: the group was killed
    Interrupted,  // we got `signal` (SIGINT, SIGTERM, SIGHUP): the group was killed
    NotStarted,   // `error` says why
  };
  Ending ending = Ending::NotStarted;
  int exitCode = 0;
  int signal = 0;
  std::string error;
  std::string tail;  // the last tailBytes of its stdout
};

// Runs `argv` (argv[0] a path to an executable) with stdin from /dev/null, stdout read as
// described above and stderr shared with ours; returns once the child has ended and every
// process left in its group has been killed.
ChildResult runChild(const std::vector<std::string>& argv, const ChildOptions& options);

}  // namespace memograph::cli
