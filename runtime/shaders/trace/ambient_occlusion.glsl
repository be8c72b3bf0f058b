// Ray-traced ambient occlusion (seeds/004 §3.1; Zhukov et al. 1998): the cosine-weighted
// fraction of the hemisphere above a point that no geometry within a distance blocks,
// (1/pi) * integral of V(w) cos(theta) dw. Written once for every caller that traces from a
// hit: the AO integrator (--integrator ao) and the Ambient Occlusion node's per-hit input.
// Needs the trace backend's traceClosest and traceShadow, rng.glsl and path_shading.glsl's
// basisAround and offsetRayOrigin first.

// Cycles' AO node settings (Blender's Inside and Only Local), as bits.
const uint kAmbientOcclusionInside = 1u;     // trace into the object: N flipped
const uint kAmbientOcclusionOnlyLocal = 2u;  // only the hit's own instance occludes
// Only Local walks through other instances with closest-hit rays (no any-hit shader or
// candidate filtering is needed, so both trace backends run it); a ray that crosses more
// surfaces of other instances than this counts as unoccluded.
const uint kAmbientOcclusionLocalSteps = 8u;

// A direction about unit `n` with density cos(theta) / pi, from u in [0,1)^2: a uniform point
// of the unit disk lifted onto the hemisphere (Malley's method; seeds/004 §3.1.2 samples the
// hemisphere stochastically per surfel, as Cycles' AO node does).
vec3 cosineDirectionAround(vec3 n, vec2 u) {
  float r = sqrt(u.x);
  float phi = 2.0 * kPi * u.y;
  vec3 t, b;
  basisAround(n, t, b);
  return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u.x)) * n);
}

// Whether instance `instance` crosses the segment origin + [0, distance] * d, ignoring every
// other instance (Only Local): up to kAmbientOcclusionLocalSteps closest hits, each ray
// starting past the last. Adds the rays traced to `rays`.
bool localOccluderAlong(vec3 origin, vec3 d, float distance, uint instance, inout uint rays) {
  float travelled = 0.0;
  for (uint step = 0u; step < kAmbientOcclusionLocalSteps; ++step) {
    rays += 1u;
    HitInfo hit = traceClosest(origin, d, distance - travelled, kRayMaskNoLightQuads);
    if (hit.t < 0.0) return false;
    if (hit.instanceIndex == instance) return true;
    travelled += hit.t;
    origin = offsetRayOrigin(origin + hit.t * d, d);
  }
  return false;
}

// The unoccluded fraction at `position` of the hit's instance `instance` over `samples`
// rays of length `distance` about `normal` (flipped with kAmbientOcclusionInside): with
// cosine-weighted directions the mean of V estimates the integral above without weights.
// The rays leave from the side of the surface (geometric normal) that `normal` points to.
// `rays` counts the rays traced.
float ambientOcclusion(vec3 position, vec3 normal, vec3 geometricNormal, uint instance,
                       float distance, uint samples, uint flags, inout Rng rng,
                       inout uint rays) {
  if (!(distance > 0.0) || samples == 0u) return 1.0;  // as Cycles: nothing to trace
  vec3 n = (flags & kAmbientOcclusionInside) != 0u ? -normal : normal;
  vec3 origin = offsetRayOrigin(position, dot(n, geometricNormal) >= 0.0 ? geometricNormal
                                                                         : -geometricNormal);
  uint unoccluded = 0u;
  for (uint i = 0u; i < samples; ++i) {
    vec3 d = cosineDirectionAround(n, rngNext2(rng));
    bool occluded;
    if ((flags & kAmbientOcclusionOnlyLocal) != 0u) {
      occluded = localOccluderAlong(origin, d, distance, instance, rays);
    } else {
      rays += 1u;
      occluded = traceShadow(origin, d, distance);
    }
    if (!occluded) unoccluded += 1u;
  }
  return float(unoccluded) / float(samples);
}

#ifdef MG_INTEGRATOR_AO
// The AO integrator's value (--integrator ao, seeds/004 §3) at the hit `s` of sample
// `sampleIndex`'s camera ray through pixel `pixelIndex`: MG_AO_SAMPLES rays of length
// MG_AO_DISTANCE_BITS (float bits) about the geometric normal facing the camera, drawn with
// the path vertex key 1 (key 0 jittered the camera ray). One function for the megakernel's
// ambientOcclusionPixel and the wavefront's pass, so at one seed both trace the same rays.
float ambientOcclusionIntegratorAt(SurfaceHit s, uint pixelIndex, uint sampleIndex,
                                   inout uint rays) {
  Rng rng = rngForPathVertex(pixelIndex, sampleIndex, 1u, frame.image.w);
  return ambientOcclusion(s.inputs.position.v, s.geometricNormal, s.geometricNormal, s.object.x,
                          uintBitsToFloat(uint(MG_AO_DISTANCE_BITS)), uint(MG_AO_SAMPLES), 0u,
                          rng, rays);
}
#endif

#ifndef MG_OMIT_TRACED_INPUTS
#include "bevel.glsl"

// The random numbers of the traced inputs at path vertex `vertexKey` (rng.glsl's key: bounce
// + 1 for the bounce-th hit) of sample `sampleIndex` of pixel `pixelIndex`: the vertex's own
// stream hashed apart, so the path's numbers stay as without the traced rays. One function
// for the megakernel and the wavefront's traced-inputs pass, so at one seed both trace the
// same rays.
Rng tracedInputsRng(uint pixelIndex, uint sampleIndex, uint vertexKey, uint seed) {
  Rng rng = rngForPathVertex(pixelIndex, sampleIndex, vertexKey, seed);
  rng.key = pcgHash(rng.key ^ 0x6A09E667u);
  return rng;
}

// Fills the traced inputs of hit `s` before its graph runs, with the settings its material's
// metadata recorded (materials.glsl): the Ambient Occlusion node's fraction
// (mg_materialAmbientOcclusion) about the interpolated shading normal, as Cycles' svm_node_ao
// with its Normal socket unlinked, and the Bevel node's normal (mg_materialBevel). Materials
// without them keep 1 and the shading normal.
void setTracedInputs(inout SurfaceHit s, Rng rng, inout uint rays) {
  uvec4 ao = mg_materialAmbientOcclusion[s.materialId];
  if (ao.y != 0u)
    s.inputs.ambientOcclusion =
        ambientOcclusion(s.inputs.position.v, s.inputs.normal, s.geometricNormal, s.object.x,
                         uintBitsToFloat(ao.x), ao.y, ao.z, rng, rays);
  uvec2 bevel = mg_materialBevel[s.materialId];
  if (bevel.y != 0u)
    s.inputs.bevelNormal =
        bevelNormal(s.inputs.position.v, s.inputs.normal, s.geometricNormal, s.object.x,
                    uintBitsToFloat(bevel.x), bevel.y, rng, rays);
}
#endif
