// Miss shader of shadow rays: nothing was in the way.
#version 460
#extension GL_EXT_ray_tracing : require

layout(location = 1) rayPayloadInEXT uint shadowPayload;

void main() {
  shadowPayload = 0u;
}
