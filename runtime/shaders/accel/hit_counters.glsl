// LiPaC's hit counters (seeds/001 §3.3.2; DynamicAccelerationStructures::hitFeedback): one
// per instance, then one per counting box (the boxes' custom index is their slot), then one
// footprint per instance (the narrowest ray cone's width at a counted hit on it, a float's
// bits, which order as the float for widths >= 0; ~0u: none; the mesh LODs' choice,
// seeds/001 §3.1.1, as §3.2.5's texture feedback keeps the finest mip level needed), then the tally of the counts the trace made, which the host checks
// against the counters' sum. Declared
// for the raygen or compute shader that counts after the trace (path_tracer.glsl).
#ifndef MG_HIT_COUNTERS_GLSL
#define MG_HIT_COUNTERS_GLSL
layout(set = 0, binding = kBindingHitFeedback, std430) buffer HitFeedbackBlock {
  uint hitCounts[];
};

// The footprint slot of an instance: the footprints sit before the tally, one per instance
// (the instances' buffer holds exactly the scene's; scene_bindings.glsl).
uint hitFootprintSlot(uint instance) {
  return uint(hitCounts.length()) - 1u - uint(instances.length()) + instance;
}
#endif
