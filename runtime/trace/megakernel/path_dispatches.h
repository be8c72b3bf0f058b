// How a frame's P paths per pixel are split over the megakernel's trace dispatches. Each
// dispatch traces a cyclic run of a pixel's paths and folds its share of the pixel's mean
// into the accumulation (path_tracer.glsl, renderPixel); the paths and their random numbers
// do not depend on the split, so the picture differs only by float rounding.
//
// Why split at all: on the GPU machine (H100, no RT cores) the unculled city at P = 6 traced
// in two dispatches (5 paths, then 1) took 0.935x the time of one dispatch of all six, at the
// same rays (docs/design/path-tracer.md, "Paths per dispatch"). LiPaC's counting frames split for
// another reason too: only the counted paths need the pipeline with the hit feedback.
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/shaders/shared_types.h"

namespace memograph::runtime {

struct PathDispatch {
  std::uint32_t firstPath = 0;  // the first of the pixel's paths it traces
  std::uint32_t pathCount = 0;  // how many, cyclically from firstPath (modulo P)
  bool adds = false;            // an earlier dispatch of the frame folded its share in already
  bool feedback = false;        // traced with LiPaC's hit-feedback pipeline

  gpu::TraceDispatchPush push() const;
};

// The paths of a LiPaC counting frame that count (FrameConstants::culling, countedPath in
// path_tracer.glsl): `count` of P from `first` on.
struct CountedPaths {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

// The counted paths of counting frame `countingIndex` when `feedbackPaths` of P count (0 or
// at least P: all of them), as the shader picks them.
CountedPaths countedPaths(std::uint32_t pathsPerPixel, std::uint32_t feedbackPaths,
                          std::uint32_t countingIndex);

// A frame's dispatches, in the order they run: P paths in runs of at most `pathsPerDispatch`
// (0: all in one). `counting`: a counting frame, whose dispatches use the feedback pipeline;
// with `splitCounted` only the counted paths do (traced last, in runs of their own), the
// others without it. Throws std::invalid_argument for P = 0 or counted paths outside P.
std::vector<PathDispatch> planPathDispatches(std::uint32_t pathsPerPixel,
                                             std::uint32_t pathsPerDispatch, bool counting,
                                             bool splitCounted, CountedPaths counted);

}  // namespace memograph::runtime
