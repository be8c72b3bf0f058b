#include "runtime/trace/integrator.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "runtime/renderer.h"

namespace memograph::runtime {

const char* integratorName(Integrator integrator) {
  return integrator == Integrator::AmbientOcclusion ? "ao" : "path";
}

Integrator parseIntegrator(const std::string& text) {
  if (text == "path")
    return Integrator::Path;
  if (text == "ao")
    return Integrator::AmbientOcclusion;
  throw std::invalid_argument("--integrator takes path or ao, not '" + text + "'");
}

float defaultAmbientOcclusionDistance(const Scene& scene) {
  bool any = false;
  glm::vec3 lo(0.0f), hi(0.0f);
  for (const Instance& instance : scene.instances) {
    if (instance.mesh >= scene.meshes.size() || scene.meshes[instance.mesh].positions.empty())
      continue;
    const Bounds b = meshBounds(scene.meshes[instance.mesh]);
    // The 8 corners of the object-space box, transformed: a box around the world-space mesh.
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y,
                        (corner & 4) ? b.hi.z : b.lo.z);
      const glm::vec3 w = glm::vec3(instance.objectToWorld * glm::vec4(p, 1.0f));
      lo = any ? glm::min(lo, w) : w;
      hi = any ? glm::max(hi, w) : w;
      any = true;
    }
  }
  const float diagonal = any ? glm::length(hi - lo) : 0.0f;
  return diagonal > 0.0f && std::isfinite(diagonal) ? kAmbientOcclusionDistanceOfDiagonal * diagonal
                                                    : 1.0f;
}

float resolveAmbientOcclusionDistance(const AmbientOcclusionOptions& options, const Scene& scene) {
  return options.distance > 0.0f ? options.distance : defaultAmbientOcclusionDistance(scene);
}

void validateIntegratorOptions(const RendererOptions& options) {
  const AmbientOcclusionOptions& ao = options.ambientOcclusion;
  if (!std::isfinite(ao.distance) || ao.distance < 0.0f)
    throw std::invalid_argument(
        "--ao-distance takes a distance >= 0 (0: a tenth of the scene's diagonal)");
  if (ao.samples == 0)
    throw std::invalid_argument("--ao-samples takes a number of rays >= 1");
  if (options.integrator != Integrator::AmbientOcclusion)
    return;
  if (options.cache.mode != CacheMode::None)
    throw std::invalid_argument(
        "--integrator ao evaluates no material, so there is nothing to cache: drop --cache");
  if (options.culling.mode != CullingMode::None)
    throw std::invalid_argument(
        "--integrator ao needs every instance in the TLAS (an AO ray must see what the camera "
        "does not): drop --culling");
  if (options.debugCacheMisses)
    throw std::invalid_argument("--debug-misses needs --integrator path");
}

std::vector<std::string> ambientOcclusionDefines(std::uint32_t samples, float distance) {
  char bits[16];
  std::snprintf(bits, sizeof bits, "0x%08Xu", std::bit_cast<std::uint32_t>(distance));
  return {"MG_INTEGRATOR_AO=1", "MG_AO_SAMPLES=" + std::to_string(samples) + "u",
          std::string("MG_AO_DISTANCE_BITS=") + bits};
}

}  // namespace memograph::runtime
