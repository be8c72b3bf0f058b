// Closest-hit shader of the pipeline backend: reports the hit (thesis §5.2). With LiPaC's
// counters in the closest-hit shader (MG_CLOSEST_HIT_COUNTS, --hit-counters closest-hit), it
// also adds the ray's weight to the counter of what it hit, as §3.3.2's closest-hit shader
// does: an instance's (a path ray) or a counting box's (a probe through the boxes' TLAS);
// the custom index is the counter's slot in both.
#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "shared_types.h"
#include "trace_hit.glsl"
#ifdef MG_CLOSEST_HIT_COUNTS
#include "hit_counters.glsl"
#endif

layout(location = 0) rayPayloadInEXT HitPayload hitPayload;
hitAttributeEXT vec2 barycentrics;

void main() {
  hitPayload.hit.instanceIndex = uint(gl_InstanceCustomIndexEXT);
  hitPayload.hit.primitiveIndex = uint(gl_PrimitiveID);
  hitPayload.hit.barycentrics = barycentrics;
  hitPayload.hit.t = gl_HitTEXT;
#ifdef MG_CLOSEST_HIT_COUNTS
  if (hitPayload.feedbackWeight != 0u)
    atomicAdd(hitCounts[gl_InstanceCustomIndexEXT], hitPayload.feedbackWeight);
#endif
}
