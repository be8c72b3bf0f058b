// The memograph commands. Each takes the arguments after its name and returns an exit code
// (0 success, 1 failure, 2 usage error).
#pragma once

#include <span>
#include <string_view>

namespace memograph::cli {

struct Command {
  std::string_view name;
  std::string_view summary;
  int (*run)(std::span<const std::string_view> args);
};

int runCompile(std::span<const std::string_view> args);
int runCheck(std::span<const std::string_view> args);
int runNodes(std::span<const std::string_view> args);
int runRender(std::span<const std::string_view> args);
int runBench(std::span<const std::string_view> args);
int runDiff(std::span<const std::string_view> args);
int runBake(std::span<const std::string_view> args);
int runImportBlender(std::span<const std::string_view> args);
int runPack(std::span<const std::string_view> args);
int runSelftest(std::span<const std::string_view> args);

// Every command, in the order `memograph --help` lists them.
std::span<const Command> commands();

}  // namespace memograph::cli
