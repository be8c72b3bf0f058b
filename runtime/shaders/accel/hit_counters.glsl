// LiPaC's hit counters (seeds/001 §3.3.2; DynamicAccelerationStructures::hitFeedback): one
// per instance, then one per counting box (the boxes' custom index is their slot), then the
// tally of the counts the trace made, which the host checks against their sum. Declared
// for the raygen or compute shader that counts after the trace (path_tracer.glsl).
#ifndef MG_HIT_COUNTERS_GLSL
#define MG_HIT_COUNTERS_GLSL
layout(set = 0, binding = kBindingHitFeedback, std430) buffer HitFeedbackBlock {
  uint hitCounts[];
};
#endif
