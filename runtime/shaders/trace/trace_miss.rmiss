// Miss shader of closest-hit rays: reports the miss as t = -1.
#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "trace_hit.glsl"

layout(location = 0) rayPayloadInEXT HitPayload hitPayload;

void main() {
  hitPayload.hit.t = -1.0;
}
