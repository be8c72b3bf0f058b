// Trace backend 2: a ray-tracing pipeline whose raygen shader runs the whole path loop;
// the closest-hit and miss shaders (trace_hit.rchit, trace_miss.rmiss, trace_shadow.rmiss)
// only report the hit, as thesis §5.2 suggests.
#extension GL_EXT_ray_tracing : require
#include "trace_hit.glsl"

layout(set = 0, binding = kBindingTlas) uniform accelerationStructureEXT tlas;
layout(location = 0) rayPayloadEXT HitPayload hitPayload;
layout(location = 1) rayPayloadEXT uint shadowPayload;

// Shader-binding-table layout: miss 0 reports a miss, miss 1 clears the shadow flag.
const uint kMissClosest = 0u;
const uint kMissShadow = 1u;

HitInfo traceClosest(vec3 origin, vec3 direction, float tMax, uint mask) {
  traceRayEXT(tlas, gl_RayFlagsOpaqueEXT, mask, 0, 1, kMissClosest, origin, 0.0, direction,
              tMax, 0);
  return hitPayload.hit;
}

bool traceShadow(vec3 origin, vec3 direction, float tMax) {
  shadowPayload = 1u;
  traceRayEXT(tlas,
              gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT |
                  gl_RayFlagsSkipClosestHitShaderEXT,
              kRayMaskNoLightQuads, 0, 1, kMissShadow, origin, 0.0, direction, tMax, 1);
  return shadowPayload != 0u;
}

#ifdef MG_HIT_FEEDBACK
layout(set = 0, binding = kBindingCountingBoxes) uniform accelerationStructureEXT countingBoxes;

// The nearest counting box the ray segment crosses, as trace_query.glsl's (the closest-hit
// shader reports it): its custom index (a hit-feedback counter slot), or ~0u when the segment
// crosses none.
uint traceCountingBox(vec3 origin, vec3 direction, float tMax) {
  traceRayEXT(countingBoxes, gl_RayFlagsOpaqueEXT, kMaskCountingBox, 0, 1, kMissClosest, origin,
              0.0, direction, tMax, 0);
  return hitPayload.hit.t >= 0.0 ? hitPayload.hit.instanceIndex : 0xFFFFFFFFu;
}
#endif
