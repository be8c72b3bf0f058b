// Which camera of the built-in path each frame of `memograph bench` renders. The path is a
// closed loop of `pathCameras` cameras; timed frame j shows camera j·stride (going round
// again past the end), and the warm-up frames come before camera 0 along the loop at the
// same step, so a cache warms up on the motion that leads into the timed frames.
//
// A stride K > 1 samples an N-camera path in N/K frames. That is only a fair sample of the
// full run for stateless renders (no cache): without temporal state a frame's cost depends
// on its camera alone, not on the frames before it. The CLI refuses a stride with a cache.
#pragma once

#include <cstdint>

namespace memograph::cli {

struct BenchFramePlan {
  std::uint32_t warmup = 0;       // untimed frames first
  std::uint32_t timed = 1;        // frames measured
  std::uint32_t stride = 1;       // path cameras per timed frame
  std::uint32_t pathCameras = 1;  // cameras on the closed path
};

// Camera index for rendered frame `frame` (0-based, warm-up frames included).
inline std::uint32_t benchCameraIndex(const BenchFramePlan& plan, std::uint32_t frame) {
  const std::int64_t n = plan.pathCameras;
  const std::int64_t step = std::int64_t(frame) - std::int64_t(plan.warmup);  // < 0: warm-up
  const std::int64_t index = (step * std::int64_t(plan.stride)) % n;
  return std::uint32_t(index < 0 ? index + n : index);
}

}  // namespace memograph::cli
