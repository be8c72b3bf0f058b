// Alpha (a material's `opacity` output: OpacityOutput, PrincipledOutput's Alpha) for a path's
// rays, in both architectures (the megakernel's bounce loop, the wavefront's trace pass): the
// trace itself passes a surface of opacity alpha < 1 with probability 1 - alpha and returns the
// first surface it does not pass, so neither the bounce loop nor the wavefront's rounds change.
// The expectation is (1 - alpha) * behind + alpha * surface, Cycles 3.4's mix for a Principled
// BSDF with Alpha (scene/shader_nodes.cpp PrincipledBsdfNode::expand: Mix(Alpha,
// Transparent, Principled)); a crossing is a transparent bounce, which does not take one of
// --bounces' rays (kernel/integrator/path_state.h path_state_next, LABEL_TRANSPARENT).
// Compiled only with MG_STOCHASTIC_OPACITY. Needs path_shading.glsl, the trace backend's
// traceClosest, materials.glsl's materialStochasticOpacity and the includer's
// evaluateMaterialAtShadowHit (the switch over the maybe-transparent graphs, or the megakernel's
// callable), which transparent_shadow.glsl uses too.

// The surfaces one ray passes at most: Cycles' Max Transparent Bounces, 8 by default
// (kernel_data.integrator.transparent_max_bounce). The next surface is shaded as opaque.
// Cycles counts the crossings over the whole path and ends the path at the surface after the
// eighth (PATH_RAY_TERMINATE_ON_NEXT_SURFACE: its emission only); memograph counts them per
// ray, so that no path state carries a count: the two differ only past eight crossings.
const uint kPathTransparentHitsMax = 8u;

// A uniform number in [0, 1) for crossing `crossing` of the ray that leaves the path vertex of
// key `vertexKey` (rng.glsl's rngForPathVertex(...).key): the vertex's key hashed apart from the
// numbers the vertex draws for its light and BSDF samples (which hash dimensions 0, 1, ... of
// the same key), so a path's own numbers stay those it draws without alpha.
float opacityCrossingSample(uint vertexKey, uint crossing) {
  uint word = pcgHash(vertexKey ^ 0x510E527Fu ^ pcgHash(crossing + 0x9B05688Cu));
  return float(word >> 8u) * (1.0 / 16777216.0);
}

// The closest surface along the ray that the path does not pass: surfaces of materials that
// may be see-through (materialStochasticOpacity) are evaluated where the ray hits them, with
// the ray's Light Path state `path` and a zero ray cone (their opacity, not their shading, is
// wanted), and passed with probability 1 - opacity. The hit's t is measured from `origin`, as
// if the ray had not stopped, so that the caller's surfaceAt, ray cone and MIS distances see
// one segment (the crossings' origin offsets, a few ulps each, are left out). `rays` counts
// the segments traced past a surface. The opacity is evaluated uncached: the trace has no
// cache lookup, and only see-through materials pay for it.
HitInfo traceThroughOpacity(vec3 origin, vec3 direction, float tMax, uint mask, PathState path,
                            uint vertexKey, inout uint rays) {
  RayCone cone;
  cone.width = 0.0;
  cone.spread = 0.0;
  vec3 segmentOrigin = origin;
  float travelled = 0.0;
  for (uint crossed = 0u; crossed <= kPathTransparentHitsMax; ++crossed) {
    HitInfo hit = traceClosest(segmentOrigin, direction, tMax - travelled, mask);
    if (hit.t < 0.0) return hit;
    uint materialId = instances[hit.instanceIndex].ids.y;
    if (crossed == kPathTransparentHitsMax || !materialStochasticOpacity(materialId)) {
      hit.t += travelled;
      return hit;
    }
    SurfaceHit s = surfaceAt(hit, segmentOrigin, direction, cone);
    setPathInputs(s.inputs, path, travelled + hit.t);
    MaterialOutputs m;
    evaluateMaterialAtShadowHit(materialId, s.inputs, m);
    if (opacityCrossingSample(vertexKey, crossed) < clamp(m.opacity, 0.0, 1.0)) {
      hit.t += travelled;
      return hit;
    }
    // On through the surface: the geometric normal faces the ray, so its far side is -ng.
    segmentOrigin = offsetRayOrigin(s.inputs.position.v, -s.geometricNormal);
    travelled += hit.t;
    rays += 1u;
  }
  HitInfo none;  // not reached: the last pass through the loop returns
  none.instanceIndex = 0u;
  none.primitiveIndex = 0u;
  none.barycentrics = vec2(0.0);
  none.t = -1.0;
  return none;
}
