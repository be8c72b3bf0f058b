// Closest-hit shader of the pipeline backend: reports the hit (thesis §5.2). LiPaC's counters
// are bumped after the trace, by the raygen (path_tracer.glsl: countHitFeedback).
#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "shared_types.h"
#include "trace_hit.glsl"

layout(location = 0) rayPayloadInEXT HitPayload hitPayload;
hitAttributeEXT vec2 barycentrics;

void main() {
  hitPayload.hit.instanceIndex = uint(gl_InstanceCustomIndexEXT);
  hitPayload.hit.primitiveIndex = uint(gl_PrimitiveID);
  hitPayload.hit.barycentrics = barycentrics;
  hitPayload.hit.t = gl_HitTEXT;
}
