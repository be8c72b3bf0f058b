// Deterministic procedural helpers the built-in scene generators share: a lattice hash,
// value noise and its fBm (terrain, placement, per-object variation), and the placement
// transform of an object standing on the ground. The same numbers on every machine.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace memograph::runtime {

// Integer lattice hash -> [0, 1).
float hash2(int x, int z, std::uint32_t seed);

// Value noise in [0, 1) with a quintic fade (smooth enough for central-difference normals).
float valueNoise(float x, float z, std::uint32_t seed);

// Fractal sum of `octaves` value noises, in about [-1, 1].
float fbm(float x, float z, int octaves, std::uint32_t seed);

// Translate to p, turn by yaw about +y, scale uniformly.
glm::mat4 placed(glm::vec3 p, float yawRadians, float scale);

}  // namespace memograph::runtime
