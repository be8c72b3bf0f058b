// Where an animated mesh's rest vertex is at a time (gpu::VertexMotion), in the language the
// host (C++, GLM) and the vertex pass (GLSL, vertex_motion.comp) share, so both move a
// vertex by one definition: the built-in city's flags, and the tests' drifting meshes.
#ifndef MEMOGRAPH_VERTEX_MOTION_H
#define MEMOGRAPH_VERTEX_MOTION_H

#ifdef __cplusplus
#include <cmath>

#include "runtime/shaders/shared_types.h"
namespace memograph::runtime::gpu {
using vec3 = glm::vec3;
using std::sin;
#define MG_FUNCTION inline
#else
#define MG_FUNCTION
#endif

// The offset from `rest` (object space) at `seconds`: the drift, plus for a cloth a wave
// travelling away from its pole (x = 0) that grows with the distance from it, with a sag
// and a slow sway; the cloth's wave.y phase sets each flag apart.
MG_FUNCTION vec3 vertexMotionOffset(VertexMotion motion, vec3 rest, float seconds) {
  vec3 offset = vec3(motion.drift) * seconds;
  float clothLength = motion.wave.x;
  if (clothLength > 0.0f) {
    float phase = motion.wave.y;
    float reach = rest.x / clothLength;
    float wave = sin(3.5f * rest.x - 5.0f * seconds + phase);
    offset +=
        vec3(0.0f, -0.08f * reach * reach, reach * (0.35f * wave + 0.15f * sin(seconds + phase)));
  }
  return offset;
}

#undef MG_FUNCTION
#ifdef __cplusplus
}  // namespace memograph::runtime::gpu
#endif
#endif
