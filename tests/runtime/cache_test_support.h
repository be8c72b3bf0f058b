// Scenes and helpers the cache tests share (texel cache, tile cache, stress): a striped
// wall whose material depends on uv only, renderer options with a cache, tiny render
// settings, mean LDR-FLIP between two renders, and the counters' consistency.
#pragma once

#include <cstdint>
#include <string>

#include "runtime/renderer.h"

namespace memograph::runtime::testing {

// Stripes in u and v: depends on uv only, so the compiler marks it cacheable.
std::string stripesGraph();
// Reads the hit position: not cacheable (thesis §4.2).
std::string positionGraph();
// A striped wall facing the camera (filling the view), and optionally a sphere before it.
Scene wallScene(const std::string& wallGraph, bool sphere);
RendererOptions cacheOptions(CacheMode mode, Backend backend = Backend::Auto,
                             std::uint32_t entries = 1u << 16,
                             CacheEviction eviction = CacheEviction::Lru);
// 24x24 pixels, seed 5.
RenderSettings settings(std::uint32_t frames, std::uint32_t raysPerPath, std::uint32_t paths = 1);
double meanFlip(const HdrImage& reference, const HdrImage& test);
// Every frame's hits and misses add up to its lookups.
void expectConsistentCounters(const RenderStats& stats);

}  // namespace memograph::runtime::testing
