// Runs the memograph CLI as a user does (a shell command), for the CLI tests.
#pragma once

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

namespace memograph::testing {

struct CliRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline CliRun runCli(const std::string& arguments) {
  const std::string command = std::string(MEMOGRAPH_CLI) + " " + arguments + " 2>&1";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return run;
  std::array<char, 4096> buffer;
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) {
    run.output.append(buffer.data(), n);
  }
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace memograph::testing
