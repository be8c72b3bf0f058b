// What a trace reports, whichever backend ran it: the hit of thesis §5.2's minimal hit
// shader (instance, primitive, barycentrics, t). t < 0 means the ray missed.
#ifndef MG_TRACE_HIT_GLSL
#define MG_TRACE_HIT_GLSL
struct HitInfo {
  uint instanceIndex;
  uint primitiveIndex;
  vec2 barycentrics;
  float t;
};

// The pipeline backend's payload of closest-hit rays: the hit, and, where the closest-hit
// shader bumps LiPaC's hit counters (MG_CLOSEST_HIT_COUNTS), what it adds to the counter of
// what the ray hits (0: the ray does not count). The raygen, the miss and the hit shaders
// are compiled with the same defines, so they agree on it.
struct HitPayload {
  HitInfo hit;
#ifdef MG_CLOSEST_HIT_COUNTS
  uint feedbackWeight;
#endif
};
#endif
