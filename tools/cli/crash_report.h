// A last word when the process dies of a fatal signal: which signal, and the call stack, so
// a crash inside the renderer or the Vulkan driver on a remote machine (the GPU bundle is
// stripped and has no debugger) still says where it happened.
#pragma once

namespace memograph::cli {

// Installs handlers for SIGSEGV, SIGBUS, SIGILL and SIGFPE that write the signal and a
// backtrace (module+offset; symbolize with addr2line on the unstripped binary) to stderr,
// then let the signal end the process as it would have (exit status 128 + signal).
void installCrashReport();

}  // namespace memograph::cli
