// The path tracer's two architectures (thesis §5.2 megakernel, the wavefront prototype) and
// how a render picks one: what the wavefront cannot do, and Shading::Auto's choice.
#pragma once

#include <string>

#include <vulkan/vulkan.h>

namespace memograph::runtime {

struct RendererOptions;

// How the path tracer is organised (docs/design/wavefront.md, "Choosing the architecture"):
// one kernel that runs each path to its end, or passes over queues of paths with their state
// in memory (Laine, Karras and Aila, "Megakernels Considered Harmful", HPG 2013). The
// wavefront is a prototype (with the floor's constants or the scene's graphs). Auto: the
// wavefront where it is measured faster and does what the render asks, else the megakernel
// (resolveShading).
enum class Shading { Auto, Megakernel, Wavefront };
const char* shadingName(Shading shading);
// "auto", "megakernel" or "wavefront"; throws std::invalid_argument naming the choices.
Shading parseShading(const std::string& text);

// Refuses (std::invalid_argument, naming the option) what an explicit Shading::Wavefront
// cannot do that the options alone tell (a cache on the floor, the subgroup tile fill; the
// scene's and device's gaps render() refuses), and wavefrontPaths with
// Shading::Megakernel (with Auto, render() checks it once resolved). The same list decides
// Auto (resolveShading).
void validateWavefrontOptions(const RendererOptions& options);

// What the device and the render bring to Shading::Auto's choice.
struct ShadingDevice {
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  // The wavefront can launch its traces: the query backend, or the pipeline backend with
  // vkCmdTraceRaysIndirectKHR.
  bool wavefrontTraces = true;
};

struct ShadingChoice {
  Shading shading = Shading::Megakernel;  // Megakernel or Wavefront, never Auto
  std::string whyMegakernel;              // Auto's reason when it chose the megakernel
};
// The architecture a render runs: options.shading unless Auto; Auto is the wavefront on a
// GPU when it does everything asked, else the megakernel (never a refusal).
ShadingChoice resolveShading(const RendererOptions& options, const ShadingDevice& device);

// What the wavefront prototype cannot do that the options ask, in words that follow "it"
// ("--shading wavefront is a prototype: it ...", or auto's reason); empty when it can.
std::string wavefrontOptionGap(const RendererOptions& options);
// The same for the device, after the options' gaps.
std::string wavefrontGap(const RendererOptions& options, const ShadingDevice& device);

}  // namespace memograph::runtime
