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

// Unbounded recursion, as a scene importer on a hierarchy 20,000 deep: the handler must run
// on its own stack, since the overflowed one has no room for it.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winfinite-recursion"  // the point of the test
[[gnu::noinline]] int recurseForever(int depth) {
  char frame[256];
  frame[depth % 256] = static_cast<char>(depth);
  // An empty asm that reads the frame after the call: the compiler can neither drop the
  // frame nor turn the recursion into a loop.
  const int below = recurseForever(depth + 1);
  asm volatile("" : : "r"(frame) : "memory");
  return below + frame[depth % 256];
}
#pragma GCC diagnostic pop

TEST(CrashReportTest, AStackOverflowIsStillReported) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        cli::installCrashReport();
        recurseForever(0);
      },
      ::testing::KilledBySignal(SIGSEGV), "memograph: fatal signal SIGSEGV.*Call stack:");
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
