// The clock warm-up (runtime/vk/clock_warmup.h): every invocation runs a chain of dependent
// integer multiply-adds and nothing else, so the GPU is busy for as long as the host keeps
// submitting it. The one store, which no chain reaches in practice, keeps the loop from being
// removed as dead code.
#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(local_size_x = 256) in;
layout(buffer_reference, std430) buffer Sink {
  uint value;
};
layout(push_constant) uniform Push {
  uvec2 sink;  // device address of one uint
  uint iterations;
}
push;

void main() {
  uint x = gl_GlobalInvocationID.x + 1u;
  for (uint i = 0u; i < push.iterations; ++i)
    x = x * 1664525u + 1013904223u;
  if (x == 0xFFFFFFFFu)
    Sink(push.sink).value = x;
}
