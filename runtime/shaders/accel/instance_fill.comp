// The GPU instance fill (seeds/001 §3.3.2: "the TLAS instance buffer is assembled on the GPU
// every frame"): from the frame's instance states and resident BLAS addresses, writes the
// TLAS records in the host fill's order (DynamicAccelerationStructures::prepareFrame): the
// active instances whose BLAS is resident into the scene's records; the omitted instances'
// counting boxes, then the boxed hitboxes', into the boxes' records; each in index order.
// One work group walks the candidates in chunks, a prefix sum over each chunk giving every
// kept record its slot, so the order (and the TLAS built from it) does not depend on
// scheduling.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "shared_types.h"

layout(local_size_x = kInstanceFillWorkgroup) in;
layout(push_constant) uniform Push {
  InstanceFillPush push;
};

// VkAccelerationStructureInstanceKHR: a row-major 3x4 transform, custom index | mask << 24,
// hit-record offset | flags << 24, the BLAS address.
struct InstanceRecord {
  vec4 rows[3];
  uint indexAndMask;
  uint offsetAndFlags;
  uvec2 blas;
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RecordTemplates {
  InstanceRecord templates[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RecordsOut {
  InstanceRecord records[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Words {
  uint words[];
};
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Addresses {
  uvec2 addresses[];
};

shared uint kept[kInstanceFillWorkgroup];

uint stateByte(uint i) {
  return (Words(push.frame.xy).words[i >> 2u] >> ((i & 3u) * 8u)) & 0xFFu;
}

// Candidate k: [0, n) an instance's own record, [n, 2n) its counting box, [2n, 2n + h) a
// hitbox's box. Returns whether it is kept, and its record.
bool candidate(uint k, out InstanceRecord record) {
  uint n = push.counts.x;
  if (k < n) {
    if (stateByte(k) != kInstanceStateActive) return false;
    uint mesh = Words(push.sources.xy).words[k];
    uvec2 blas = Addresses(push.sources.zw).addresses[mesh];
    if (blas == uvec2(0u)) return false;  // waiting for its build
    record = RecordTemplates(push.templates.xy).templates[k];
    record.blas = blas;
    return true;
  }
  if (k < 2u * n) {
    if (stateByte(k - n) != kInstanceStateOmitted) return false;
    record = RecordTemplates(push.templates.zw).templates[k - n];
    return true;
  }
  if (stateByte(k - n) == 0u) return false;  // a hitbox without a box
  record = RecordTemplates(push.templates.zw).templates[k - n];
  return true;
}

// Candidates [first, end) into the records at `target`, in order.
void fill(uint first, uint end, uvec2 target) {
  uint lane = gl_LocalInvocationID.x;
  uint base = 0u;
  for (uint start = first; start < end; start += kInstanceFillWorkgroup) {
    InstanceRecord record;
    bool keep = start + lane < end && candidate(start + lane, record);
    kept[lane] = keep ? 1u : 0u;
    barrier();
    // Inclusive prefix sum over the chunk (Hillis and Steele).
    for (uint offset = 1u; offset < kInstanceFillWorkgroup; offset <<= 1u) {
      uint add = lane >= offset ? kept[lane - offset] : 0u;
      barrier();
      kept[lane] += add;
      barrier();
    }
    if (keep) RecordsOut(target).records[base + kept[lane] - 1u] = record;
    base += kept[kInstanceFillWorkgroup - 1u];
    barrier();
  }
}

void main() {
  uint n = push.counts.x;
  fill(0u, n, push.frame.zw);
  if (push.counts.zw != uvec2(0u)) fill(n, 2u * n + push.counts.y, push.counts.zw);
}
