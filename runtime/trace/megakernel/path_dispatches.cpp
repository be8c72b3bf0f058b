#include "runtime/trace/megakernel/path_dispatches.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace memograph::runtime {

gpu::TraceDispatchPush PathDispatch::push() const {
  gpu::TraceDispatchPush p{};
  p.paths = gpu::uvec4(firstPath, pathCount, adds ? 1u : 0u, 0u);
  return p;
}

CountedPaths countedPaths(std::uint32_t pathsPerPixel, std::uint32_t feedbackPaths,
                          std::uint32_t countingIndex) {
  if (pathsPerPixel == 0)
    return {};
  const std::uint32_t count =
      feedbackPaths == 0 || feedbackPaths >= pathsPerPixel ? pathsPerPixel : feedbackPaths;
  // path_tracer.glsl's countedPath: (frame.culling.y * counted) % P, in 32-bit arithmetic.
  return {std::uint32_t(countingIndex * count) % pathsPerPixel, count};
}

namespace {

// Appends `count` paths from `first` (cyclic modulo P) in runs of at most `runLength`.
void appendRuns(std::vector<PathDispatch>& dispatches, std::uint32_t pathsPerPixel,
                std::uint32_t first, std::uint32_t count, std::uint32_t runLength, bool feedback) {
  for (std::uint32_t done = 0; done < count;) {
    PathDispatch d;
    d.firstPath = (first + done) % pathsPerPixel;
    d.pathCount = std::min(runLength, count - done);
    d.adds = !dispatches.empty();
    d.feedback = feedback;
    dispatches.push_back(d);
    done += d.pathCount;
  }
}

}  // namespace

std::vector<PathDispatch> planPathDispatches(std::uint32_t pathsPerPixel,
                                             std::uint32_t pathsPerDispatch, bool counting,
                                             bool splitCounted, CountedPaths counted) {
  if (pathsPerPixel == 0)
    throw std::invalid_argument("planPathDispatches: no paths per pixel");
  if (counting &&
      (counted.count == 0 || counted.count > pathsPerPixel || counted.first >= pathsPerPixel))
    throw std::invalid_argument(
        "planPathDispatches: counted paths " + std::to_string(counted.first) + "+" +
        std::to_string(counted.count) + " outside " + std::to_string(pathsPerPixel) + " paths");
  const std::uint32_t runLength =
      pathsPerDispatch == 0 ? pathsPerPixel : std::min(pathsPerDispatch, pathsPerPixel);
  std::vector<PathDispatch> dispatches;
  if (counting && splitCounted && counted.count < pathsPerPixel) {
    // The others first, from the path after the counted run, then the counted run.
    appendRuns(dispatches, pathsPerPixel, (counted.first + counted.count) % pathsPerPixel,
               pathsPerPixel - counted.count, runLength, false);
    appendRuns(dispatches, pathsPerPixel, counted.first, counted.count, runLength, true);
  } else {
    appendRuns(dispatches, pathsPerPixel, 0, pathsPerPixel, runLength, counting);
  }
  return dispatches;
}

}  // namespace memograph::runtime
