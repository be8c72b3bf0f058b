// `memograph bake` on the device (docs/guide/bake.md): evaluates one compiled material graph at
// the pixel centres of its UV square in a compute shader (runtime/shaders/materials/bake.comp) and
// reads back every MaterialOutputs member. One baker (one Vulkan device, one shader
// compiler with its disk cache) bakes any number of materials, one compute shader each.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "runtime/host/image.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

struct BakeSettings {
  std::uint32_t width = 64;
  std::uint32_t height = 64;
  // The object's bounding box in object space (= world space: the object sits at the
  // origin, unrotated). The bake plane spans it in x and y at its centre in z; Generated
  // coordinates use Blender's automatic texture space of it. Default: Blender's default
  // plane (size 2).
  std::array<float, 3> boundsMin = {-1.0f, -1.0f, 0.0f};
  std::array<float, 3> boundsMax = {1.0f, 1.0f, 0.0f};
  // The shading normal (unit) over the whole plane; the geometric normal and the view stay
  // +Z. A tilted one stands for a mesh with custom normals, as Cycles' bakes of nodes that
  // read the normal (Box projection) need.
  std::array<float, 3> normal = {0.0f, 0.0f, 1.0f};
};

// One material to bake: the compiler's GLSL include and its textures (in slot order).
struct BakeMaterial {
  std::string name;  // EvaluateMaterial_<name>
  std::string glsl;
  std::vector<TextureImage> textures;
};

// Every MaterialOutputs member at pixel (i, j), row-major with row j = 0 at v near 0
// (uv = ((i + 0.5) / W, (j + 0.5) / H)): index j * width + i.
struct BakeOutputs {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::array<float, 3>> baseColor;
  std::vector<float> metallic;
  std::vector<float> roughness;
  std::vector<float> specular;
  std::vector<float> specularTint;
  std::vector<float> cyclesPrincipled;
  std::vector<std::array<float, 3>> normal;
  std::vector<std::array<float, 3>> emission;
  std::vector<float> opacity;
};

class MaterialBaker {
 public:
  // `shaderCacheDirectory`: the SPIR-V disk cache and the device's pipeline cache (empty:
  // neither).
  MaterialBaker(const ContextOptions& options, std::filesystem::path shaderCacheDirectory);
  ~MaterialBaker();
  MaterialBaker(const MaterialBaker&) = delete;
  MaterialBaker& operator=(const MaterialBaker&) = delete;

  const VulkanContext& context() const { return *context_; }

  // Throws std::runtime_error (a shader that does not compile, a device error) or
  // std::invalid_argument (a size the device cannot hold).
  BakeOutputs bake(const BakeMaterial& material, const BakeSettings& settings);

  // Runs the bake's evaluation `dispatches` times into device memory, one dispatch after
  // the other, and returns each dispatch's GPU time in nanoseconds (timestamp queries);
  // nothing is read back. Each pixel stores one float, the sum of every output component
  // (bake.comp's MG_BAKE_TIMING), so that the stores do not bound a cheap evaluation. Throws as
  // bake() does, and std::runtime_error on a device without timestamps. Untimed dispatches
  // run first (bakeWarmUpDispatches), so that the GPU's clocks are up when the timing starts.
  std::vector<double> timeDispatches(const BakeMaterial& material, const BakeSettings& settings,
                                     std::uint32_t dispatches);

 private:
  class BakeProgram;
  std::unique_ptr<VulkanContext> context_;
  std::filesystem::path shaderCacheDirectory_;
};

// Untimed dispatches that MaterialBaker::timeDispatches runs before it times, for a probe
// dispatch of `probeNs`: about a quarter of a second of work, at least 1 and at most 4096
// (4096 when the probe timed nothing).
std::uint32_t bakeWarmUpDispatches(double probeNs);

}  // namespace memograph::runtime
