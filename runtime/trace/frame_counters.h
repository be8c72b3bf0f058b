// The per-frame counters of FrameStats by name, so summaries (`memograph bench --csv`) can
// report a median of each without knowing every field: a counter added to FrameStats and
// listed here shows up in the bench summary with no change to the CLI.
#pragma once

#include <string_view>
#include <vector>

#include "runtime/trace/render_stats.h"

namespace memograph::runtime {

struct FrameCounter {
  std::string_view name;  // a CSV column stem: lower case, underscores
  double value = 0.0;
  bool peak = false;  // summaries report its largest value too (memory)
};

// The counters of one frame, always the same names in the same order (the bench CSV's
// header is built from a default FrameStats). Times and the frame index are not counters.
std::vector<FrameCounter> frameCounters(const FrameStats& frame);

}  // namespace memograph::runtime
