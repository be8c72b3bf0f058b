// LiPaC's hit feedback (seeds/001 §3.3.2) as both architectures count it: which pixels and
// paths count in a counting frame, with what weight, and the counts of one invocation through
// a two-slot buffer into the counters. The megakernel (path_tracer.glsl) counts every path
// ray of its pixel's paths; the wavefront's trace pass (wavefront.glsl) counts the one ray it
// traces. The same pixels, paths and weights in both, so at one seed they count the same
// sums. Needs FrameConstants `frame`, hit_counters.glsl's `hitCounts` and the backend's
// traceCountingBox; the host defines MG_HIT_FEEDBACK where LiPaC counts.
#ifndef MG_HIT_FEEDBACK_GLSL
#define MG_HIT_FEEDBACK_GLSL
#include "hit_counters.glsl"

// The paths of a pixel that count this frame (CullingOptions::feedbackPaths): N of P, from
// the counting frame's index on; every path where N is 0 or at least P.
uint sampledPathCount(uint pathCount) {
  uint counted = frame.culling.z;
  return counted == 0u || counted >= pathCount ? pathCount : counted;
}
bool countedPath(uint path, uint pathCount) {
  uint counted = sampledPathCount(pathCount);
  uint first = (frame.culling.y * counted) % pathCount;
  return (path + pathCount - first) % pathCount < counted;
}

// A path ray counts the instance it hit, and a probe along the same segment through the
// counting boxes' own TLAS counts the nearest box it crosses before that hit (a hitbox, or an
// omitted instance's box: the custom index is the counter slot), as the thesis's hitbox
// closest-hit shader registers the hit and masks out the other boxes: one box per ray, and
// path rays never traverse a box.
//
// The counts of an invocation go through a two-slot buffer first: the P camera rays of a
// pixel mostly hit one instance, and the bounces of its paths keep returning to a few (the
// ground, the facade in front), so a run of equal slots costs one atomic instead of one a
// ray, and the counters most rays hit (the ground's) see far fewer same-address atomics.
// The sums are the same, so the states and the picture are too.
//
// The counts this invocation made, added after the frame's counters (the buffer's last uint)
// so that the host can check they all arrived (addHitFeedbackTally).
uint g_feedbackTally = 0u;
uvec2 g_feedbackSlots = uvec2(0xFFFFFFFFu);
uvec2 g_feedbackCounts = uvec2(0u);

// Adds a slot's count to its counter; the caller then reuses the slot or is done with it.
void writeFeedbackSlot(uint i) {
  if (g_feedbackCounts[i] != 0u) atomicAdd(hitCounts[g_feedbackSlots[i]], g_feedbackCounts[i]);
}

void bufferHitFeedback(uint slot, uint weight) {
  g_feedbackTally += weight;
  if (slot == g_feedbackSlots.x) {
    g_feedbackCounts.x += weight;
  } else if (slot == g_feedbackSlots.y) {
    g_feedbackCounts.y += weight;
  } else {
    // The older slot goes; the newer becomes the older.
    writeFeedbackSlot(1u);
    g_feedbackSlots.y = g_feedbackSlots.x;
    g_feedbackCounts.y = g_feedbackCounts.x;
    g_feedbackSlots.x = slot;
    g_feedbackCounts.x = weight;
  }
}

// Mesh LODs (seeds/001 §3.1.1; like §3.2.5's feedback of the finest mip level a texture
// needs): the narrowest ray cone that reached an instance in a counted ray, which the host's
// LOD choice compares with each level's error, so that what a mirror magnifies keeps its
// detail where its distance alone would not. A run of hits on one instance keeps its minimum
// here and writes it once. Both architectures write them: the megakernel from surfaceAt's
// cone width, the wavefront's trace pass from the cone its path state carries.
uint g_footprintInstance = 0xFFFFFFFFu;
float g_footprintWidth = 0.0;

void writeHitFootprint() {
  if (g_footprintInstance != 0xFFFFFFFFu)
    atomicMin(hitCounts[hitFootprintSlot(g_footprintInstance)], floatBitsToUint(g_footprintWidth));
}

// A counted hit on `instance` whose cone was `width` wide there (negative past a focus).
void bufferHitFootprint(uint instance, float width) {
  float footprint = abs(width);
  if (!(footprint < 3.0e38)) return;  // no NaN or infinity among the bits atomicMin orders
  if (instance == g_footprintInstance) {
    g_footprintWidth = min(g_footprintWidth, footprint);
    return;
  }
  writeHitFootprint();
  g_footprintInstance = instance;
  g_footprintWidth = footprint;
}

// What is still buffered, once the invocation's rays are done.
void flushHitFeedback() {
  writeFeedbackSlot(0u);
  writeFeedbackSlot(1u);
  writeHitFootprint();
}

// `weight` 0: this ray does not count this frame (hitFeedbackWeight, pathFeedbackWeight).
void countHitFeedback(vec3 origin, vec3 direction, HitInfo hit, uint weight) {
  if (weight == 0u) return;
  if (hit.t >= 0.0) bufferHitFeedback(hit.instanceIndex, weight);
  uint box = traceCountingBox(origin, direction, hit.t >= 0.0 ? hit.t : kRayTMax);
  if (box != 0xFFFFFFFFu) bufferHitFeedback(box, weight);
}

// Sampled feedback (CullingOptions::feedbackStride = N): 1 in N blocks of 8×8 pixels counts
// its rays, weighted N, a different block each counting frame (frame.culling.y: with
// --feedback-every K the frames that count are 0, K, 2K, ..., whose own indices picked the
// same blocks every time at K = N, and the small city's static camera never settled). Whole
// blocks, so that neighbouring invocations, which mostly share a subgroup (the query
// backend's 8×8 work groups; the pipeline's launch order is the driver's), skip the probe
// together.
uint hitFeedbackWeight(uvec2 pixel) {
  uint stride = max(frame.culling.x, 1u);
  uvec2 block = pixel >> 3u;
  return (block.x + 5u * block.y + frame.culling.y) % stride == 0u ? stride : 0u;
}

// Sampled paths (CullingOptions::feedbackPaths = N, frame.culling.z; 0: every path): N of
// the pixel's P paths count their rays, weighted P / N besides the block's weight, other
// paths each counting frame. The same paths in every pixel, so a subgroup, whose lanes run
// path p together, skips the probes together; and every pixel counts, so what a few pixels
// see is counted in every counting frame (which 1 block in N would not do).
uint pathFeedbackWeight(uint path, uint pathCount, uint weight) {
  return countedPath(path, pathCount) ? weight * (pathCount / sampledPathCount(pathCount))
                                      : 0u;
}

// The invocation's tally into the buffer's last uint, once it flushed its counts; with
// MG_SUBGROUP_RAY_COUNT every invocation of the subgroup must come here.
void addHitFeedbackTally() {
#ifdef MG_SUBGROUP_RAY_COUNT
  uint subgroupTally = subgroupAdd(g_feedbackTally);
  if (subgroupElect() && subgroupTally > 0u) atomicAdd(hitCounts[hitCounts.length() - 1], subgroupTally);
#else
  if (g_feedbackTally > 0u) atomicAdd(hitCounts[hitCounts.length() - 1], g_feedbackTally);
#endif
}
#endif  // MG_HIT_FEEDBACK_GLSL
