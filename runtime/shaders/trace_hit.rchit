// Closest-hit shader of the pipeline backend: reports the hit and nothing else (thesis §5.2).
#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "trace_hit.glsl"

layout(location = 0) rayPayloadInEXT HitInfo hitPayload;
hitAttributeEXT vec2 barycentrics;

void main() {
  hitPayload.instanceIndex = uint(gl_InstanceCustomIndexEXT);
  hitPayload.primitiveIndex = uint(gl_PrimitiveID);
  hitPayload.barycentrics = barycentrics;
  hitPayload.t = gl_HitTEXT;
}
