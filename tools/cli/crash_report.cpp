// Fatal-signal report: signal name and backtrace on stderr, then the default action.
#include "crash_report.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <vector>

namespace memograph::cli {

namespace {

void writeText(const char* text) {
  // write(2) is async-signal-safe; a short write of a diagnostic is not worth a retry loop.
  [[maybe_unused]] auto written = ::write(STDERR_FILENO, text, std::strlen(text));
}

void reportFatalSignal(int signal) {
  // glibc's own names ("SEGV", "Segmentation fault"): lookups in static tables, no locale
  // and no allocation, unlike strsignal().
  writeText("memograph: fatal signal SIG");
  writeText(sigabbrev_np(signal));
  writeText(" (");
  writeText(sigdescr_np(signal));
  writeText(
      "): a bug in memograph or the Vulkan driver; please report it with the command line. "
      "Call stack:\n");
  void* frames[64];
  const int count = ::backtrace(frames, 64);
  ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // SA_RESETHAND restored the default action: re-raising ends the process with the signal's
  // status, as without the handler.
  ::raise(signal);
}

}  // namespace

void installCrashReport() {
  // backtrace() loads libgcc's unwinder on first use, which allocates: do it now, not
  // inside the handler.
  void* warmUp[1];
  ::backtrace(warmUp, 1);
  // A stack overflow (deep recursion in a scene importer, say) leaves no stack for the
  // handler: it runs on its own stack, allocated once and kept for the process's life.
  static std::vector<char> alternateStack(std::max<std::size_t>(SIGSTKSZ, 64 * 1024));
  stack_t stack{};
  stack.ss_sp = alternateStack.data();
  stack.ss_size = alternateStack.size();
  ::sigaltstack(&stack, nullptr);
  struct sigaction action {};
  action.sa_handler = reportFatalSignal;
  action.sa_flags = SA_RESETHAND | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGSEGV, SIGBUS, SIGILL, SIGFPE})
    ::sigaction(signal, &action, nullptr);
}

}  // namespace memograph::cli
