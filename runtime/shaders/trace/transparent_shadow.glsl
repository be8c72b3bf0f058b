// Transparent shadows, for both architectures (the megakernel's sampleDirectLight, the
// wavefront's shadow pass): a shadow ray passes through the surfaces of materials that may be
// transparent (the linker's materialTransparentShadow: the graph calls TransparentBsdf or
// writes an opacity below 1), attenuated at each by the summed weight of the Transparent lobes
// its graph writes there and the share its opacity lets through (transparencyOf),
// as Cycles 3.4 does by default (kernel/integrator/intersect_shadow.h
// integrate_intersect_shadow_transparent, shade_shadow.h integrate_transparent_shadow,
// kernel/closure/bsdf.h's transparent extinction). Compiled only with MG_TRANSPARENT_SHADOWS.
// Needs path_shading.glsl, the trace backend's traceClosest, and the includer's
// evaluateMaterialAtShadowHit (materials.glsl's switch over the maybe-transparent graphs, or
// the megakernel's callable).

// The transparent surfaces a shadow ray passes at most: Cycles' transparent_max_bounce, 8 by
// default (intersect_shadow.h integrate_shadow_max_transparent_hits); the next one it meets
// is opaque. Cycles 3.4 passes eight and stops at the ninth (the Blender scene
// transparent_shadows, tests/blender/scenes/build_scene.py, measures it). Cycles starts the
// count at the path's own transparent bounces; memograph's path does not count them, so its
// shadow rays start at 0.
const uint kShadowTransparentHitsMax = 8u;

// The transparency of a material's outputs at a shadow hit: the summed weight of its
// Transparent lobes (Cycles' shader_bsdf_transparency, closure_transparent_extinction), and
// with MG_STOCHASTIC_OPACITY the see-through share of its opacity alpha: Cycles expands a
// Principled BSDF's Alpha into Mix(Alpha, Transparent, surface) (shader_nodes.cpp
// PrincipledBsdfNode::expand), whose transparent weight is (1 - alpha) + alpha * the surface's.
vec3 transparencyOf(MaterialOutputs m) {
  vec3 transparency = vec3(0.0);
#ifndef MG_OMIT_BSDF_LOBES
  int count = min(m.lobeCount, MG_MAX_LOBES);
  for (int i = 0; i < MG_MAX_LOBES; ++i)
    if (i < count && int(m.lobeWeight[i].w) == MG_LOBE_TRANSPARENT)
      transparency += max(m.lobeWeight[i].rgb, vec3(0.0));
#endif
#ifdef MG_STOCHASTIC_OPACITY
  float alpha = clamp(m.opacity, 0.0, 1.0);
  transparency = vec3(1.0 - alpha) + alpha * transparency;
#endif
  return transparency;
}

// The fraction of light that the segment from origin along the unit direction, up to tMax,
// lets through: 0 where an opaque surface (or the transparent surface past the limit) blocks
// it, else the product of the transparencies of the surfaces it crosses, nearest first.
// Each surface's graph runs at the hit with the shadow ray's state `shadowPath`
// (shadowPathState), a zero ray cone and no traced inputs (Cycles evaluates a shadow hit
// without its AO and Bevel nodes' rays). `rays` counts the segments traced past a surface.
vec3 traceShadowTransmittance(vec3 origin, vec3 direction, float tMax, PathState shadowPath,
                              inout uint rays) {
  vec3 transmittance = vec3(1.0);
  RayCone cone;
  cone.width = 0.0;
  cone.spread = 0.0;
  for (uint crossed = 0u; crossed <= kShadowTransparentHitsMax; ++crossed) {
    HitInfo hit = traceClosest(origin, direction, tMax, kRayMaskNoLightQuads);
    if (hit.t < 0.0) return transmittance;
    uint materialId = instances[hit.instanceIndex].ids.y;
    if (crossed == kShadowTransparentHitsMax || !materialTransparentShadow(materialId))
      return vec3(0.0);
    SurfaceHit s = surfaceAt(hit, origin, direction, cone);
    setPathInputs(s.inputs, shadowPath, hit.t);
    MaterialOutputs m;
    evaluateMaterialAtShadowHit(materialId, s.inputs, m);
    transmittance *= transparencyOf(m);
    if (all(equal(transmittance, vec3(0.0)))) return vec3(0.0);
    // On through the surface: the geometric normal faces the ray, so its far side is -ng.
    origin = offsetRayOrigin(s.inputs.position.v, -s.geometricNormal);
    tMax -= hit.t;
    rays += 1u;
  }
  return vec3(0.0);
}
