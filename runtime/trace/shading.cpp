#include "runtime/trace/shading.h"

#include <stdexcept>

#include "runtime/renderer.h"

namespace memograph::runtime {

const char* shadingName(Shading shading) {
  switch (shading) {
    case Shading::Auto:
      return "auto";
    case Shading::Wavefront:
      return "wavefront";
    case Shading::Megakernel:
      break;
  }
  return "megakernel";
}

Shading parseShading(const std::string& text) {
  if (text == "auto")
    return Shading::Auto;
  if (text == "megakernel")
    return Shading::Megakernel;
  if (text == "wavefront")
    return Shading::Wavefront;
  throw std::invalid_argument("--shading takes auto, megakernel or wavefront, not '" + text + "'");
}

std::string wavefrontOptionGap(const RendererOptions& options) {
  const CacheOptions& cache = options.cache;
  if (cache.mode != CacheMode::None && options.floorMaterials)
    return "it fills the cache in its material passes, and the free-material floor has none "
           "(time the floor's lookups with --shading megakernel)";
  if (cache.mode == CacheMode::Tile &&
      (cache.tileFill == TileFill::Subgroup || cache.groupByMaterial || cache.testRepacks))
    return "it computes missing tiles from the deferred fill's queue; --tile-fill subgroup and "
           "its grouping and test hook are the megakernel's";
  return {};
}

std::string wavefrontGap(const RendererOptions& options, const ShadingDevice& device) {
  std::string gap = wavefrontOptionGap(options);
  if (!gap.empty())
    return gap;
  if (!device.wavefrontTraces)
    return "on the pipeline backend it launches its traces with vkCmdTraceRaysIndirectKHR, "
           "which the device lacks (use --backend query)";
  return {};
}

void validateWavefrontOptions(const RendererOptions& options) {
  if (options.shading == Shading::Megakernel && options.wavefrontPaths > 0)
    throw std::invalid_argument(
        "--wavefront-paths sets the wavefront's paths in flight; it needs --shading wavefront");
  // Auto: render() decides once it knows the device and the scene.
  if (options.shading != Shading::Wavefront)
    return;
  const std::string gap = wavefrontOptionGap(options);
  if (!gap.empty())
    throw std::invalid_argument("--shading wavefront is a prototype: " + gap);
}

// Auto: the wavefront on a GPU. On an NVIDIA H200 (1920x1080, P = 6, L = 4, the pipeline
// backend) it was faster than the megakernel in all eight configurations measured
// (docs/design/wavefront.md, "Choosing the architecture"): the classroom 47.6 against 73.1 ms on
// the floor, 96.7 against 2762 ms without a cache, 93.5 against 148.4 ms with the texel cache,
// 95.0 against 181.6 ms with the tile cache; the landscape 23.3 against 30.6, 33.6 against
// 203.7, 32.6 against 77.5 and 31.8 against 96.5 ms. Sorting hits by material keeps a GPU's
// lanes on one graph, where the megakernel's lanes diverge over many. On lavapipe (a CPU) the
// two could not be ranked (the megakernel ahead on the floor, 34.9 against 38.5 ms), so it
// keeps the megakernel. Anything the wavefront prototype cannot do (wavefrontGap) picks the
// megakernel too; an explicit --shading wavefront is refused for it instead. Culling (frustum
// and LiPaC), animated meshes and the debug views are the frame loop's, which runs either
// architecture the same way, LiPaC's counts are hit_feedback.glsl's in both, and an emitter's
// graph at a light sample is a material pass after the shadow pass, so none of them is a gap.
ShadingChoice resolveShading(const RendererOptions& options, const ShadingDevice& device) {
  if (options.shading != Shading::Auto)
    return {options.shading, ""};
  if (device.type == VK_PHYSICAL_DEVICE_TYPE_CPU)
    return {Shading::Megakernel,
            "the device is a CPU, where the wavefront was not measured faster"};
  // The AO integrator's megakernel is one short loop (a camera ray, then its AO rays) with
  // no material to diverge on: the wavefront's round trip through the path state is only a
  // cost (H100, 8 AO rays a pixel at 1080p: the classroom 3.47 against 3.88 ms, the
  // landscape 7.52 against 7.96 ms; docs/results.md, "Ambient occlusion rays").
  // --shading wavefront runs it.
  if (options.integrator == Integrator::AmbientOcclusion)
    return {Shading::Megakernel,
            "the AO integrator evaluates no material, where the megakernel measured faster"};
  const std::string gap = wavefrontGap(options, device);
  if (!gap.empty())
    return {Shading::Megakernel, "the wavefront prototype cannot do what is asked: " + gap};
  return {Shading::Wavefront, ""};
}

}  // namespace memograph::runtime
