// What a render computes per pixel: the thesis §5.2 path tracer, or the ray-traced ambient
// occlusion workload of seeds/004 §3 (each pixel's primary hit, N cosine-weighted rays of a
// maximum distance, the unoccluded fraction), and the settings of the latter.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace memograph::runtime {

struct RendererOptions;
struct Scene;

enum class Integrator { Path, AmbientOcclusion };
const char* integratorName(Integrator integrator);  // "path" or "ao"
// "path" or "ao"; throws std::invalid_argument naming the choices.
Integrator parseIntegrator(const std::string& text);

struct AmbientOcclusionOptions {
  // Rays longer than this find nothing (world units); 0: the scene's scale,
  // defaultAmbientOcclusionDistance.
  float distance = 0.0f;
  // AO rays from each primary hit (seeds/004 §3.1.2: samples per surfel, SPS).
  std::uint32_t samples = 16;
};

// The fraction of the diagonal of the scene's world-space bounds that the default AO distance
// is: a tenth reaches the neighbouring geometry of a room or a street, not across the scene
// (which would darken everything evenly). seeds/004 §3 leaves the distance to the scene.
constexpr float kAmbientOcclusionDistanceOfDiagonal = 0.1f;

// kAmbientOcclusionDistanceOfDiagonal times the diagonal of the box around every instance's
// transformed mesh bounds; 1 for a scene without extent.
float defaultAmbientOcclusionDistance(const Scene& scene);

// `options.distance`, or the scene's default where it is 0.
float resolveAmbientOcclusionDistance(const AmbientOcclusionOptions& options, const Scene& scene);

// Refuses (std::invalid_argument, naming the option) what the AO integrator cannot do: a
// material cache (it evaluates no material), culling (an AO ray must see every instance, not
// only those the camera's paths found), a negative or non-finite distance, zero samples.
void validateIntegratorOptions(const RendererOptions& options);

// The path tracer's defines for the AO integrator (path_tracer.glsl, ambient_occlusion.glsl):
// MG_INTEGRATOR_AO, the samples, and the distance as float bits (exact in any locale).
std::vector<std::string> ambientOcclusionDefines(std::uint32_t samples, float distance);

}  // namespace memograph::runtime
