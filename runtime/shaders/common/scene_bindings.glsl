// The path tracer's scene and frame bindings (descriptor set 0, shared_types.h), declared
// once for every shader that shades paths: the megakernel (path_tracer.glsl) and the
// wavefront passes (wavefront.glsl).
layout(set = 0, binding = kBindingFrame, std140) uniform FrameBlock {
  FrameConstants frame;
};
layout(set = 0, binding = kBindingAccumulation, std430) buffer AccumulationBlock {
  vec4 accumulation[];
};
layout(set = 0, binding = kBindingVertices, std430) readonly buffer VertexBlock {
  Vertex vertices[];
};
layout(set = 0, binding = kBindingIndices, std430) readonly buffer IndexBlock {
  uint indices[];
};
layout(set = 0, binding = kBindingInstances, std430) readonly buffer InstanceBlock {
  Instance instances[];
};
layout(set = 0, binding = kBindingMeshes, std430) readonly buffer MeshBlock {
  Mesh meshes[];
};
layout(set = 0, binding = kBindingLights, std430) readonly buffer LightBlock {
  Light lights[];
};
layout(set = 0, binding = kBindingEnvironment, std430) readonly buffer EnvironmentBlock {
  vec4 environmentTexels[];
};
layout(set = 0, binding = kBindingRayCounter, std430) buffer CounterBlock {
  Counters counters;
};

const float kRayTMax = 1e30;
