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

// The pipeline backend's payload of closest-hit rays: the hit.
struct HitPayload {
  HitInfo hit;
};
#endif
