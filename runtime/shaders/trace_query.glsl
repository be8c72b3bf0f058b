// Trace backend 1: rays traced inline from the compute shader with VK_KHR_ray_query.
#extension GL_EXT_ray_query : require
#include "trace_hit.glsl"

layout(set = 0, binding = kBindingTlas) uniform accelerationStructureEXT tlas;

// Closest opaque hit along a ray between tMin and tMax, or t = -1. The cull mask stays a
// constant: lavapipe compiled a non-constant one three times slower and ran it about a
// thousand times slower (camera rays skip lights' quads in traceVisible instead).
HitInfo traceClosest(vec3 origin, vec3 direction, float tMin, float tMax) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, tlas, gl_RayFlagsOpaqueEXT, 0xFF, origin, tMin, direction, tMax);
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

// Whether anything blocks the segment from origin to origin + tMax * direction. Lights'
// quads (instance mask 0x01, InstancePlacement::castsShadow) cast no shadow.
bool traceShadow(vec3 origin, vec3 direction, float tMax) {
  rayQueryEXT query;
  rayQueryInitializeEXT(query, tlas,
                        gl_RayFlagsOpaqueEXT | gl_RayFlagsTerminateOnFirstHitEXT, 0xFE,
                        origin, 0.0, direction, tMax);
  while (rayQueryProceedEXT(query)) {
  }
  return rayQueryGetIntersectionTypeEXT(query, true) !=
         gl_RayQueryCommittedIntersectionNoneEXT;
}
