// The options of `render` and `bench`, declared once (option_table.cpp): each entry's name,
// typed value, default, help, section and the modes that use it drive the parsing, the
// help text (--help, --help-all), the notes for options a mode leaves unused, and the CLI
// reference (docs/guide/cli.md).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/renderer.h"

namespace memograph::cli {

// The commands that share the table.
enum class TraceCommand { Render, Bench };

struct ImageSize {
  std::uint32_t width = 0, height = 0;
};

// `--frame-range A:B`: frames A..B of the path, both included.
struct FrameRange {
  std::uint32_t first = 0, last = 0;
};

// What `render` and `bench` were asked for, as typed values: the renderer's options and a
// frame's settings (the runtime's types), and each command's own.
struct TraceCommandOptions {
  runtime::RendererOptions renderer;
  // render: the settings; bench: those of every run, each at its size of `sizes`.
  runtime::RenderSettings settings;
  bool noEmissiveNee = false;  // a scene option: applied to each scene loaded

  // render
  std::string out, materials, cameraPath, environment, stats, debugCulling;
  bool listDevices = false, debugMisses = false;
  std::optional<FrameRange> frameRange;
  std::uint32_t warmupFrames = 0;
  bool resume = false;

  // bench
  std::vector<ImageSize> sizes;
  std::uint32_t warmup = 0, frameStride = 1;
  std::optional<std::uint32_t> cameraFrames;
  std::optional<double> timeLimitSeconds;
  std::string label, csv, framesCsv, pipelineStatistics;
  bool staticCamera = false;

  // The options given, by declared name, in the order met.
  std::vector<std::string_view> given;
  bool wasGiven(std::string_view name) const;
};

// Scans `args` for `command`: the table's options (`--x V` or `--x=V`), `--help`/`-h`
// (`intro`, then the common options), `--help-all` (every option), and positional
// arguments (into `positional`; `--` ends the options). Each value is checked against its
// declared type as it is read. Returns nullopt for the command to go on, or the exit code
// it returns now: a usage error's (printed), or kExitOk after printing the help.
std::optional<int> scanTraceOptions(TraceCommand command, std::span<const std::string_view> args,
                                    std::string_view intro, TraceCommandOptions& options,
                                    std::vector<std::string>& positional);

// The checks that span options (the runtime's ranges and combinations) and the test hook
// MEMOGRAPH_TEST_TILE_GIVE_UP. Throws std::invalid_argument with a message for the user.
void validateTraceOptions(TraceCommandOptions& options);

// "--x is ignored: it needs ..." for each option given that the chosen modes leave unused
// (accepted, so that a script may pass one set of flags to every mode it measures).
std::vector<std::string> ignoredOptionNotes(const TraceCommandOptions& options);

// The options' help, grouped by section: the common ones, or all with `all`.
std::string traceOptionHelp(TraceCommand command, bool all);

}  // namespace memograph::cli
