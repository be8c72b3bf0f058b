#include "runtime/scene/builtin/procedural.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace memograph::runtime {

// Integer lattice hash → [0, 1) (PCG-style mixing), so terrain and placement are the
// same on every machine.
float hash2(int x, int z, std::uint32_t seed) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 73856093u ^
                    static_cast<std::uint32_t>(z) * 19349663u ^ seed * 83492791u;
  h = h * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return static_cast<float>(h >> 8u) / 16777216.0f;
}

// Value noise with a quintic fade: smooth enough for central-difference normals.
float valueNoise(float x, float z, std::uint32_t seed) {
  const float fx = std::floor(x), fz = std::floor(z);
  const int ix = static_cast<int>(fx), iz = static_cast<int>(fz);
  const float tx = x - fx, tz = z - fz;
  const auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const float u = fade(tx), v = fade(tz);
  const float a = hash2(ix, iz, seed), b = hash2(ix + 1, iz, seed);
  const float c = hash2(ix, iz + 1, seed), d = hash2(ix + 1, iz + 1, seed);
  return glm::mix(glm::mix(a, b, u), glm::mix(c, d, u), v);
}

float fbm(float x, float z, int octaves, std::uint32_t seed) {
  float sum = 0, amplitude = 0.5f, frequency = 1;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * (valueNoise(x * frequency, z * frequency, seed + i) * 2 - 1);
    amplitude *= 0.5f;
    frequency *= 2.03f;  // not exactly 2, so octaves do not align on the lattice
  }
  return sum;
}

glm::mat4 placed(glm::vec3 p, float yawRadians, float scale) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), p);
  m = glm::rotate(m, yawRadians, glm::vec3(0, 1, 0));
  return glm::scale(m, glm::vec3(scale));
}

}  // namespace memograph::runtime
