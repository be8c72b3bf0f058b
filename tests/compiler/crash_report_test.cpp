// The CLI's fatal-signal report (tools/cli/crash_report.h): a crash says which signal and
// prints a call stack on stderr, then still ends the process with that signal, so scripts
// see the same exit status (128 + signal) as without the report.
#include "crash_report.h"

#include <gtest/gtest.h>

#include <csignal>

namespace memograph {
namespace {

TEST(CrashReportTest, AFatalSignalIsNamedWithACallStackAndStillEndsTheProcess) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        cli::installCrashReport();
        std::raise(SIGSEGV);
      },
      ::testing::KilledBySignal(SIGSEGV),
      "memograph: fatal signal SIGSEGV \\(Segmentation fault\\).*Call stack:");
  // The stack names this executable's frames (module and offset, for addr2line).
  EXPECT_EXIT(
      {
        cli::installCrashReport();
        std::raise(SIGBUS);
      },
      ::testing::KilledBySignal(SIGBUS),
      "SIGBUS \\(Bus error\\)(.|\n)*memograph_compiler_tests\\(");
}

TEST(CrashReportTest, WithoutASignalNothingIsPrinted) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        cli::installCrashReport();
        std::exit(0);
      },
      ::testing::ExitedWithCode(0), "^$");
}

}  // namespace
}  // namespace memograph
