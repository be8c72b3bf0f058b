// Trace backend 1: rays traced inline from the compute shader with VK_KHR_ray_query.
#extension GL_EXT_ray_query : require
#include "trace_hit.glsl"

layout(set = 0, binding = kBindingTlas) uniform accelerationStructureEXT tlas;

// Closest opaque hit along a ray, or t = -1. `mask`: the TLAS cull mask (camera rays
// kRayMaskNoLightQuads skip lights' quads, InstancePlacement::castsShadow). Each
// initialization gets a constant mask (lavapipe compiled the traversal of a non-constant
// one far more slowly); the one rayQueryProceedEXT loop keeps one inlined traversal.
HitInfo traceClosest(vec3 origin, vec3 direction, float tMax, uint mask) {
  rayQueryEXT query;
  if (mask == kRayMaskAll)
    rayQueryInitializeEXT(query, tlas, gl_RayFlagsOpaqueEXT, kRayMaskAll, origin, 0.0, direction,
                          tMax);
  else
    rayQueryInitializeEXT(query, tlas, gl_RayFlagsOpaqueEXT, kRayMaskNoLightQuads, origin, 0.0,
                          direction, tMax);
  while (rayQueryProceedEXT(query)) {
  }
  HitInfo hit;
  hit.t = -1.0;
  hit.instanceIndex = 0u;
  hit.primitiveIndex = 0u;
  hit.barycentrics = vec2(0.0);
  if (rayQueryGetIntersectionTypeEXT(query, true) ==
      gl_RayQueryCommittedIntersectionTriangleEXT) {
    hit.instanceIndex = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
    hit.primitiveIndex = uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
    hit.barycentrics = rayQueryGetIntersectionBarycentricsEXT(query, true);
    hit.t = rayQueryGetIntersectionTEXT(query, true);
  }
  return hit;
}

// Whether anything blocks the segment from origin to origin + tMax * direction.
bool traceShadow(vec3 origin, vec3 direction, float tMax) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, tlas,
                        gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT,
                        kRayMaskNoLightQuads, origin, 0.0, direction, tMax);
  while (rayQueryProceedEXT(query)) {
  }
  return rayQueryGetIntersectionTypeEXT(query, true) !=
         gl_RayQueryCommittedIntersectionNoneEXT;
}

#ifdef MG_HIT_FEEDBACK
layout(set = 0, binding = kBindingCountingBoxes) uniform accelerationStructureEXT countingBoxes;

// The nearest counting box the ray segment crosses (seeds/001 §3.3.2: the hitboxes'
// closest-hit shader registers the hit; a traversal that stopped at the first box it found
// could count one behind it): its custom index (a hit-feedback counter slot), or ~0u when the
// segment crosses none.
uint traceCountingBox(vec3 origin, vec3 direction, float tMax) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, countingBoxes, gl_RayFlagsOpaqueEXT, kMaskCountingBox, origin,
                        0.0, direction, tMax);
  while (rayQueryProceedEXT(query)) {
  }
  if (rayQueryGetIntersectionTypeEXT(query, true) != gl_RayQueryCommittedIntersectionTriangleEXT)
    return 0xFFFFFFFFu;
  return uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
}
#endif
