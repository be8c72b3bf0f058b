// The vertex pass (seeds/001 §3.3.1): moves the animated meshes the frame needs to the
// frame's time, in the scene's vertex buffer, before their BLASes are updated or rebuilt.
// Work group row y is job y (one mesh); invocation x is its vertex x. Each vertex's normal
// is the area-weighted sum of its triangles' normals, their corners moved here too, so no
// invocation waits for another's positions: one dispatch, one barrier after it.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "shared_types.h"
#include "vertex_motion.h"

layout(local_size_x = kVertexMotionWorkgroup) in;
layout(push_constant) uniform Push {
  VertexMotionPush push;
};

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Jobs {
  VertexMotionJob jobs[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Rest {
  VertexMotionRest rest[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Corners {
  uvec4 corners[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vertices {
  Vertex vertices[];
};

vec3 moved(VertexMotion motion, uint restVertex, float seconds) {
  vec3 position = Rest(push.sources.zw).rest[restVertex].position.xyz;
  return position + vertexMotionOffset(motion, position, seconds);
}

void main() {
  VertexMotionJob job = Jobs(push.sources.xy).jobs[gl_WorkGroupID.y];
  uint v = gl_GlobalInvocationID.x;
  if (v >= job.range.y) return;
  float seconds = push.time.x;
  uint restVertex = job.range.z + v;
  VertexMotionRest self = Rest(push.sources.zw).rest[restVertex];
  // The triangles in index order, as the mesh lists them (Mesh::indices).
  vec3 normal = vec3(0.0);
  for (uint k = 0u; k < self.triangles.y; ++k) {
    uvec4 t = Corners(push.targets.xy).corners[self.triangles.x + k];
    vec3 a = moved(job.motion, t.x, seconds);
    normal += cross(moved(job.motion, t.y, seconds) - a, moved(job.motion, t.z, seconds) - a);
  }
  float area = length(normal);
  normal = area > 1e-20 ? uintBitsToFloat(job.range.w) * normal / area : self.normal.xyz;
  Vertices scene = Vertices(push.targets.zw);
  uint target = job.range.x + v;
  // xyz only: w holds the texture coordinates, which do not move.
  scene.vertices[target].position.xyz =
      self.position.xyz + vertexMotionOffset(job.motion, self.position.xyz, seconds);
  scene.vertices[target].normal.xyz = normal;
}
