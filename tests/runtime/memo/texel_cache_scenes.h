// Scenes and measures shared by the texel and tile cache tests: a striped (cacheable) wall,
// a per-hit (not cacheable) material, renderer options with a cache, tiny render
// settings, mean LDR-FLIP between two renders and the counters' consistency.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/renderer.h"
#include "tools/quality/flip.h"

namespace memograph::runtime::testing {

// Stripes in u and v: depends on uv only, so the compiler marks it cacheable.
inline std::string stripesGraph() {
  return "material Stripes;\nUVInput UV>0;\nWave In<0 Out>1;\nBaseColorOutput Color<1;\n"
         "RoughnessOutput Roughness=0.7;\n";
}

// Reads the shading normal: not cacheable (thesis §4.2), and per hit, so it has no cut
// either (a position would be a world-space cut, which the texel cache keys).
inline std::string perHitGraph() {
  return "material Shaded;\nNormalInput Out>0;\nWave In<0 Out>1;\nBaseColorOutput "
         "Color<1;\n";
}

// A striped wall facing the camera (filling the view), and optionally a sphere before it.
inline Scene wallScene(const std::string& wallGraph, bool sphere) {
  Scene scene;
  scene.meshes.push_back(quad(8.0f, 4.0f));
  scene.materials.push_back({"Wall", "", wallGraph});
  // The quad lies in y = 0 with normal +y; a quarter turn about x turns it to face +z.
  scene.instances.push_back(
      {0, 0, glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0))});
  if (sphere) {
    scene.meshes.push_back(testing::sphere(16));
    scene.materials.push_back({"Ball", "", constantGraph("Ball", {0.7f, 0.3f, 0.2f}, 0.3f)});
    scene.instances.push_back({1, 1, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 1.5f))});
  }
  scene.lights.push_back({LightType::Point, {1, 2, 4}, {0, -1, 0}, glm::vec3(15.0f)});
  scene.environment.constantRadiance = {0.3f, 0.3f, 0.3f};
  scene.camera.position = {0, 0, 5};
  scene.camera.target = {0, 0, 0};
  return scene;
}

// A camera panning along a long striped wall (thesis Fig. 6.14's setting): 32 frames of
// 24x24, each bringing new texels, so a 1024-entry cache fills after a few frames.
inline Scene panningWallScene() {
  Scene scene;
  scene.meshes.push_back(quad(64.0f, 32.0f));
  scene.materials.push_back({"Wall", "", stripesGraph()});
  scene.instances.push_back(
      {0, 0, glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0))});
  scene.environment.constantRadiance = {0.5f, 0.5f, 0.5f};
  return scene;
}

inline RenderSettings panningSettings() {
  RenderSettings s;
  s.width = 24;
  s.height = 24;
  s.raysPerPath = 1;
  s.frames = 32;
  s.seed = 5;
  for (std::uint32_t f = 0; f < s.frames; ++f) {
    Camera camera;
    camera.position = {-20.0f + 0.4f * float(f), 0.0f, 5.0f};
    camera.target = camera.position - glm::vec3(0.0f, 0.0f, 5.0f);
    s.cameraPath.push_back(camera);
  }
  return s;
}

inline double meanFlip(const HdrImage& reference, const HdrImage& test) {
  FlipImageView a{reference.rgba, int(reference.width), int(reference.height), 4};
  FlipImageView b{test.rgba, int(test.width), int(test.height), 4};
  FlipOptions options;
  options.encoding = FlipEncoding::Linear;
  return computeFlip(a, b, options).mean;
}

inline RendererOptions cacheOptions(CacheMode mode, Backend backend = Backend::Auto,
                                    std::optional<std::uint32_t> entries = 1u << 16,
                                    CacheEviction eviction = CacheEviction::Lru) {
  RendererOptions options = testOptions(backend);
  options.cache.mode = mode;
  options.cache.entries = entries;
  options.cache.eviction = eviction;
  return options;
}

// 24x24 pixels, seed 5.
inline RenderSettings cacheSettings(std::uint32_t frames, std::uint32_t raysPerPath,
                                    std::uint32_t paths = 1) {
  RenderSettings s;
  s.width = 24;
  s.height = 24;
  s.pathsPerPixel = paths;
  s.raysPerPath = raysPerPath;
  s.frames = frames;
  s.seed = 5;
  return s;
}

// 32x32 primary hits (L = 1), one path a pixel, seed 5: the filter, refresh and cut-key tests.
inline RenderSettings primaryHitSettings(std::uint32_t frames) {
  RenderSettings s = cacheSettings(frames, 1);
  s.width = 32;
  s.height = 32;
  return s;
}

// Every frame's hits and misses add up to its lookups.
inline void expectConsistentCounters(const RenderStats& stats) {
  for (const FrameStats& f : stats.frames) {
    EXPECT_EQ(f.cacheHits + f.cacheMisses, f.cacheLookups) << "frame " << f.frame;
    EXPECT_LE(f.cacheOccupancy, stats.cacheEntries) << "frame " << f.frame;
  }
}

}  // namespace memograph::runtime::testing
