// The wavefront path tracer (--shading wavefront): the path loop of path_tracer.glsl split
// into passes that each run over a queue of paths, with the paths' state in memory between
// them (Laine, Karras and Aila, "Megakernels Considered Harmful", HPG 2013, §4). One source,
// one pass per compile, selected by the host's define:
// - MG_WAVEFRONT_GENERATE: camera rays of one round (path `round` of every pixel) into the
//   path state; the live queue holds every pixel;
// - MG_WAVEFRONT_TRACE: the closest hit of every live path (the only passes besides the
//   shadow pass that trace: a compute shader with ray queries, or the raygen of a ray-tracing
//   pipeline launched indirectly);
// - with material graphs (no MG_MATERIAL_FLOOR), the hits sorted by material and each
//   material's graph evaluated for its batch (the paper's §4: one kernel per material):
//   MG_WAVEFRONT_BIN_COUNT counts the live hits of each bin (one bin per distinct graph),
//   MG_WAVEFRONT_BIN_OFFSETS turns the counts into an exclusive prefix sum and the bins'
//   indirect arguments, MG_WAVEFRONT_BIN_SCATTER writes the hits' slots into the
//   material-sorted queue, and MG_WAVEFRONT_MATERIAL (compiled once per distinct graph with
//   only its include, "material.glsl") evaluates its bin's hits into the path state;
// - with materials that read a traced input (Ambient Occlusion, Bevel: no
//   MG_OMIT_TRACED_INPUTS), MG_WAVEFRONT_TRACED_INPUTS between the scatter and the material
//   passes traces their rays from the hits of those materials alone (the bin offsets pass puts
//   their bins first in the material-sorted queue) with the megakernel's estimators
//   (ambient_occlusion.glsl, bevel.glsl) and keeps the results for the material passes
//   (docs/design/traced-inputs.md): a compute shader with ray queries, or a raygen of the
//   ray-tracing pipeline, as the trace pass; with the AO integrator (MG_INTEGRATOR_AO,
//   --integrator ao) the same pass computes the integrator's AO at every live path's camera
//   hit, and a round is generate, trace, this pass and finish;
// - with the texel cache (MG_CACHE_TEXEL), MG_WAVEFRONT_LOOKUP first looks up every live hit
//   of a whole uv-only material (thesis §5.3): a hit's cached values become its material
//   outputs and only the misses are binned; the material passes insert what they evaluate
//   (lock, values, unlock, as the megakernel's evaluateMaterialCached does); with
//   MG_CACHE_CUTS a material that is not cacheable as a whole is keyed by its cut (thesis §7;
//   texel_cache.glsl cacheCutKeyFor): the lookup reads the cut's entry and a found one's
//   values go into the path state (MG_WAVEFRONT_CUT_FIELD), a missing one's hit is binned
//   and its material pass evaluates the cut at the key's centre, inserts it and stores the
//   values likewise; the shade pass runs the rest of the graph from them (the host's
//   material_rests.glsl). A graph that reads a traced input runs its rest in its material
//   pass. A read with a filter (MG_CACHE_FILTER) runs in the material pass, in place (the
//   megakernel's evaluateMaterialThroughCut), as does the rest; with the tile cache
//   (MG_CACHE_TILE, its deferred fill's queue) the lookup reads the hit's tile and queues a
//   missing one, and each bin's material pass also computes its bin's queued tiles, one
//   invocation a texel, so the next bounce finds them;
// - MG_WAVEFRONT_SHADE: the material's outputs (the floor's constants, or the material
//   pass's, or the rest of a cut graph from the cut's values), emission, one light sample
//   (its shadow ray into the shadow queue) and the BSDF sample (the path into the next live
//   queue);
// - MG_WAVEFRONT_QUEUE: one invocation turns the queues' counts into the next passes'
//   indirect arguments;
// - MG_WAVEFRONT_SHADOW: traces the queued shadow rays and adds the unblocked contributions;
//   with emitters whose emission NEE takes from their graphs (MG_NEE_EVALUATES_EMISSION) it
//   queues such an emitter's unblocked samples instead, and the binning and material passes
//   run once more over their points (push.chunk.w's kWavefrontLightPoints), each graph's pass
//   adding the contribution times the emission it evaluates at its points;
// - MG_WAVEFRONT_FINISH: folds the round's radiance into the pixel's sum, and after the last
//   round the mean into the accumulation buffer (as the megakernel's renderPixel does).
// With LiPaC (MG_HIT_FEEDBACK) the trace pass counts its rays as the megakernel does
// (hit_feedback.glsl); with --debug-misses the lookup pass flags a pixel's misses for the
// finish pass.
// Shading is path_shading.glsl's, the megakernel's own; random numbers are counter-based
// (rng.glsl), keyed by pixel, sample, bounce and dimension, so no pass order changes a sample,
// and with the megakernel's keys: at one seed both architectures trace the same paths.
#version 460
#extension GL_GOOGLE_include_directive : require
#ifdef MG_SUBGROUP_RAY_COUNT
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif
#if defined(MG_WAVEFRONT_MATERIAL) ||                                       \
    (defined(MG_WAVEFRONT_SHADE) && defined(MG_WAVEFRONT_CUT_FIELD)) ||   \
    (defined(MG_WAVEFRONT_SHADOW) && defined(MG_TRANSPARENT_SHADOWS)) || \
    (defined(MG_WAVEFRONT_TRACE) && defined(MG_STOCHASTIC_OPACITY))
#extension GL_EXT_nonuniform_qualifier : require  // material_textures.glsl
#endif
#ifdef MG_CACHE_CLOCK_COUNTER
// The texel cache's 64-bit counter clock (§5.3.3): gpu::Counters::cacheClock is a uint64_t.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#endif

#define MG_WAVEFRONT 1
#include "shared_types.h"
#include "materials.glsl"
#include "rng.glsl"
#include "brdf.glsl"
#include "bsdf_lobes.glsl"
#include "ray_cone.glsl"

#if defined(MG_WAVEFRONT_TRACE) || defined(MG_WAVEFRONT_SHADOW) || \
    defined(MG_WAVEFRONT_TRACED_INPUTS)
#ifdef MG_BACKEND_QUERY
#include "trace_query.glsl"
#else
#include "trace_pipeline.glsl"
#endif
#else
#include "trace_hit.glsl"
#endif

#include "scene_bindings.glsl"
#if defined(MG_HIT_FEEDBACK) && defined(MG_WAVEFRONT_TRACE)
// LiPaC's counts (seeds/001 §3.3.2): the trace pass counts its rays as the megakernel counts
// the same rays (the pixels, paths and weights of hit_feedback.glsl).
#include "hit_feedback.glsl"
#endif
#if defined(MG_MATERIAL_FLOOR)
#include "material_floor.glsl"
#elif defined(MG_WAVEFRONT_MATERIAL)
#ifdef MG_MATERIAL_INSTANCES
// Float k of the bin's parameter block: the constants in which the graphs sharing this pass
// differ (material_instances.h). Defined below the push constants, which name the bin.
float materialParameter(int k);
#define MG_MATERIAL_PARAMETER(k) materialParameter(k)
#endif
// One distinct graph's include (the host's "material.glsl"; its EvaluateMaterial_<Name> is
// MG_EVALUATE_MATERIAL, its first texture slot MG_TEXTURE_BASE), as a material callable has;
// or the shared include of graphs of one shape, each bin one of them.
#include "material.glsl"
#include "material_textures.glsl"
#ifdef MG_CACHE_TEXEL
// The megakernel's names for evaluating a material, for texel_cache.glsl's in-place
// read-or-fill (evaluateMaterialCached, evaluateMaterialThroughCut), which this pass runs
// where a hit reads more entries than one (--cache-filter): a material pass has one graph, so
// the scene material id is its own.
void evaluateMaterialDirect(uint materialId, MaterialInputs inputs,
                            out MaterialOutputs outputs) {
  MG_EVALUATE_MATERIAL(inputs, outputs);
}
#ifdef MG_CACHE_CUTS
void evaluateMaterialCutSwitch(uint materialId, MaterialInputs inputs,
                               out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
#ifdef MG_EVALUATE_MATERIAL_CUT
  MG_MATERIAL_CUT cut;
  MG_EVALUATE_MATERIAL_CUT(inputs, cut);
  for (uint i = 0u; i < uint(MG_MATERIAL_CUT_WIDTH); ++i) values[i] = cut.v[i];
#endif
}

void evaluateMaterialRestSwitch(uint materialId, MaterialInputs inputs,
                                float values[MG_CACHE_VALUES], out MaterialOutputs outputs) {
#ifdef MG_EVALUATE_MATERIAL_CUT
  MG_MATERIAL_CUT cut;
  for (uint i = 0u; i < uint(MG_MATERIAL_CUT_WIDTH); ++i) cut.v[i] = values[i];
  MG_EVALUATE_MATERIAL_REST(inputs, cut, outputs);
#else
  MG_EVALUATE_MATERIAL(inputs, outputs);
#endif
}
#endif  // MG_CACHE_CUTS
#endif  // MG_CACHE_TEXEL
#endif
#if (defined(MG_WAVEFRONT_SHADOW) && defined(MG_TRANSPARENT_SHADOWS)) || \
    (defined(MG_WAVEFRONT_TRACE) && defined(MG_STOCHASTIC_OPACITY))
// The maybe-transparent graphs and their switch, evaluateMaterialAtShadowHit (the host's
// shadow_materials.glsl): the shadow pass evaluates them where its rays hit them, and the
// trace pass where its rays hit a surface of opacity maybe below 1, in place, as the megakernel
// does (transparent_shadow.glsl, stochastic_opacity.glsl).
#include "shadow_materials.glsl"
#include "material_textures.glsl"
#endif
#include "path_shading.glsl"
#if defined(MG_WAVEFRONT_SHADOW) && defined(MG_TRANSPARENT_SHADOWS)
#include "transparent_shadow.glsl"
#endif
#if defined(MG_WAVEFRONT_TRACE) && defined(MG_STOCHASTIC_OPACITY)
#include "stochastic_opacity.glsl"
#endif
#ifdef MG_WAVEFRONT_TRACED_INPUTS
#include "ambient_occlusion.glsl"  // setTracedInputs, the megakernel's; bevel.glsl with it
#endif
// The texel cache where it is read (the lookup pass) and written (the material passes); the
// tile cache also where its queued tiles are binned.
#if defined(MG_WAVEFRONT_LOOKUP) && defined(MG_SUBGROUP_RAY_COUNT)
#define MG_CACHE_STAMP_BY_SUBGROUP 1  // the lookup pass: every invocation reaches its end
#endif
#ifdef MG_WAVEFRONT_LOOKUP
// The lookup pass reads; only the material passes insert, each pass behind a barrier.
#define MG_CACHE_QUIESCENT_READS 1
#endif
#if defined(MG_CACHE_TEXEL) && (defined(MG_WAVEFRONT_LOOKUP) || defined(MG_WAVEFRONT_MATERIAL))
#if defined(MG_WAVEFRONT_MATERIAL) && defined(MG_EVALUATE_MATERIAL_CUT)
#define MG_CACHE_CUT_PASS 1  // this pass's graph is keyed by its cut: no whole-graph fill
#endif
#include "texel_cache.glsl"
#endif
#if defined(MG_WAVEFRONT_SHADE) && defined(MG_WAVEFRONT_CUT_FIELD)
// The rests of the graphs keyed by their cut that read no traced input (the host's
// material_rests.glsl, evaluateMaterialRestInShade): their hits reach the shade pass with the
// cut's values, from the lookup pass or their material pass.
#include "material_rests.glsl"
#include "material_textures.glsl"
#endif
#if defined(MG_CACHE_TILE) &&                                                    \
    (defined(MG_WAVEFRONT_LOOKUP) || defined(MG_WAVEFRONT_BIN_COUNT) ||          \
     defined(MG_WAVEFRONT_BIN_OFFSETS) || defined(MG_WAVEFRONT_BIN_SCATTER) ||  \
     defined(MG_WAVEFRONT_MATERIAL) || defined(MG_WAVEFRONT_QUEUE))
#ifndef MG_TILE_FILL_DEFERRED
#error the wavefront fills tiles through the deferred fill's queue (MG_TILE_FILL_DEFERRED)
#endif
#include "tile_cache.glsl"
#define MG_WAVEFRONT_TILES 1
#endif
#if defined(MG_CACHE_TEXEL) || defined(MG_CACHE_TILE)
#define MG_WAVEFRONT_CACHE 1
#endif
#ifdef MG_WAVEFRONT_TILES
// The tiles the bounce's lookups queued (tileEnqueue counts requests past the capacity too,
// and gives those up); the queue pass empties the queue for the next bounce.
uint queuedTiles() {
  return min(tileQueueHeader.count, kTileQueueCapacity);
}

// The lookup pass's read of a tile (its texel, or the bilinear blend of four), by the name
// of the texel cache's.
bool cacheRead(TileRequest request, out float values[MG_CACHE_VALUES]) {
  return tileRead(request, values);
}
const uint kTileTexelsOrZero = kTileTexels;
#else
const uint kTileTexelsOrZero = 0u;
#endif

layout(set = 0, binding = kBindingPathState, std430) buffer PathStateBlock {
  vec4 pathState[];
};
layout(set = 0, binding = kBindingPathQueues, std430) buffer PathQueueBlock {
  uint pathQueues[];
};
layout(set = 0, binding = kBindingWavefrontControl, std430) buffer WavefrontControlBlock {
  WavefrontControl control;
  uvec4 materialBins[];  // kBinRecords a bin (shared_types.h); none with the floor
};
#if defined(MG_WAVEFRONT_MATERIAL) && defined(MG_MATERIAL_INSTANCES)
// A pass shared by graphs of one shape: the host pushes each bin's graph with its dispatch,
// its first texture slot and its parameter block (shared_types.h,
// kMaterialParameterPushOffset). Push constants, not constants in the code: the pass compiles
// once whatever the constants are, and needs no descriptor of its own.
layout(push_constant) uniform WavefrontPushBlock {
  WavefrontPush push;
  ivec4 materialInstance;  // x: the bin's graph's first texture slot
#if MG_MATERIAL_PARAMETER_COUNT > 0
  float materialParameters[MG_MATERIAL_PARAMETER_COUNT];
#endif
};
#define MG_TEXTURE_BASE materialInstance.x
#if MG_MATERIAL_PARAMETER_COUNT > 0
float materialParameter(int k) {
  return materialParameters[k];
}
#endif
#else
layout(push_constant) uniform WavefrontPushBlock {
  WavefrontPush push;
};
#endif

// The path state's fields (kPathStateFields vec4 arrays, one slot per pixel): each pass
// reads and writes only the fields it needs, so a trace moves 3 of the 9.
const uint kFieldOrigin = 0u;              // xyz origin, w ray-cone width
const uint kFieldDirection = 1u;           // xyz direction, w ray-cone spread
const uint kFieldThroughput = 2u;          // rgb throughput, w the last BSDF pdf (0: camera)
const uint kFieldRadiance = 3u;            // rgb radiance so far, w the hit's t (< 0: miss)
const uint kFieldHit = 4u;                 // instance, primitive, barycentrics (uint bits)
const uint kFieldShadowOrigin = 5u;        // xyz origin, w length
const uint kFieldShadowDirection = 6u;     // xyz direction, w (uint bits) with the path state
                                           // a light point's (packLightPathState)
const uint kFieldShadowContribution = 7u;  // rgb: what the shadow ray adds when unblocked
const uint kFieldPixelSum = 8u;            // rgb: the pixel's radiance summed over rounds;
                                           // w with --debug-misses: 1 where a path missed
// With material graphs: the material's outputs at the hit (MaterialOutputs, 15 floats).
const uint kFieldMaterialBase = 9u;        // baseColor, metallic
const uint kFieldMaterialNormal = 10u;     // normal, roughness
const uint kFieldMaterialEmission = 11u;   // emission, specular
const uint kFieldMaterialRest = 12u;       // specularTint, cyclesPrincipled, opacity, and
                                           // with a cache the bin to evaluate (w)
// With graphs that read the path state (no MG_OMIT_PATH_INPUTS): PathState's ray kind and
// depths (int bits), written where the path's ray is (the generate and shade passes).
// With emitters whose light samples evaluate their graphs (MG_NEE_EVALUATES_EMISSION), after
// it: the light sample's point, for its bin's material pass. The host counts the same fields
// (WavefrontPathTracer, gpu::kPathStateFieldsFor*).
#ifndef MG_OMIT_PATH_INPUTS
const uint kFieldPathState = 13u;
const uint kFieldLightHit = 14u;           // instance, primitive, barycentrics (uint bits)
#else
const uint kFieldLightHit = 13u;
#endif
const uint kFieldLightOrigin = kFieldLightHit + 1u;  // xyz the shading point, w its t along wi
#ifdef MG_WAVEFRONT_LOBE_FIELD
// With materials of BSDF lobes (MG_BSDF_LOBES), after the fields above: lobe i's weight and
// kind (MaterialOutputs::lobeWeight) in field MG_WAVEFRONT_LOBE_FIELD + 2 i, its parameters
// in the next.
const uint kFieldLobes = uint(MG_WAVEFRONT_LOBE_FIELD);
#endif
#ifdef MG_WAVEFRONT_TRACED_FIELD
// With materials that read a traced input, after the lobes: xyz the Bevel normal, w the AO
// fraction at the hit (the traced-inputs pass's, for the material pass).
const uint kFieldTracedInputs = uint(MG_WAVEFRONT_TRACED_FIELD);
#endif
#ifdef MG_WAVEFRONT_MIN_RAY_PDF_FIELD
// With Filter Glossy (MG_FILTER_GLOSSY_INVERSE), after the fields above: x the path's
// PathState::minRayPdf, written where the path's ray is (the generate and shade passes).
const uint kFieldMinRayPdf = uint(MG_WAVEFRONT_MIN_RAY_PDF_FIELD);
#endif
#ifdef MG_WAVEFRONT_CUT_FIELD
// With cut keys read unfiltered, last: the cut's values at a hit of a graph whose rest the
// shade pass runs (mg_materialCutInfo's w), four a field, as many fields as the widest cut
// needs (MG_WAVEFRONT_CUT_FIELDS); a hit fills those its own cut needs.
const uint kFieldCut = uint(MG_WAVEFRONT_CUT_FIELD);
#endif
#ifdef MG_WAVEFRONT_PRIMARY_FIELD
// With --shared-primary, after the fields above (the host's count of them): the pixel's
// camera-ray hit, traced in round 0 and read by the later rounds' trace passes.
const uint kFieldPrimaryHit = uint(MG_WAVEFRONT_PRIMARY_FIELD);  // as kFieldHit
const uint kFieldPrimaryT = kFieldPrimaryHit + 1u;                // x the hit's t
#endif

// The path state's slots (its capacity: every pixel, or a chunk of them; push.chunk).
uint slotCount() {
  return push.chunk.x;
}

// The pixel (index into the image) whose path slot `slot` holds in this chunk: the key of its
// random numbers, so a round split into chunks draws what it draws whole.
uint pixelOfSlot(uint slot) {
  return push.chunk.y + slot;
}

uint fieldIndex(uint field, uint slot) {
  return field * slotCount() + slot;
}

// Queue q: 0 and 1 the live queues (used in turn, bounce by bounce), 2 the shadow queue, 3
// (with material graphs) the live hits' slots sorted by material bin, 4 (with the tile
// cache) the queued tiles' slots sorted by bin (the tile queue's capacity, not slotCount()).
uint queueIndex(uint queue, uint i) {
  return queue * slotCount() + i;
}

uint workgroupsFor(uint invocations) {
  return (invocations + kWavefrontWorkgroupSize - 1u) / kWavefrontWorkgroupSize;
}

// A material pass's work groups for `invocations` (kWavefrontMaterialWorkgroupSize).
uint materialWorkgroupsFor(uint invocations) {
  return (invocations + kWavefrontMaterialWorkgroupSize - 1u) / kWavefrontMaterialWorkgroupSize;
}

// Whether every round's camera ray is the pixel centre's, traced once (--shared-primary); the
// AO integrator ignores it, as the megakernel's ambientOcclusionPixel does.
bool sharesPrimaryRay() {
#ifdef MG_INTEGRATOR_AO
  return false;
#else
  return (frame.path.z & kFlagSharedPrimaryRay) != 0u;
#endif
}

// The pixel's sample index over frames: frame * P + the round's path.
uint sampleIndexOf(uint round) {
  return rngSampleIndex(frame.image.z, frame.path.x, round);
}

#if defined(MG_WAVEFRONT_TRACE) || defined(MG_WAVEFRONT_SHADOW) || \
    defined(MG_WAVEFRONT_TRACED_INPUTS)
#ifdef MG_BACKEND_QUERY
layout(local_size_x = kWavefrontWorkgroupSize) in;
uint invocationIndex() {
  return gl_GlobalInvocationID.x;
}
#else
uint invocationIndex() {
  return gl_LaunchIDEXT.x;
}
#endif
#elif defined(MG_WAVEFRONT_MATERIAL)
layout(local_size_x = kWavefrontMaterialWorkgroupSize) in;
uint invocationIndex() {
  return gl_GlobalInvocationID.x;
}
#else
layout(local_size_x = kWavefrontWorkgroupSize) in;
uint invocationIndex() {
  return gl_GlobalInvocationID.x;
}
#endif

// Reserves `count` places of queue counter counts.y (the next live queue) or, with `shadow`,
// counts.z (the shadow queue); returns the first.
uint reserveQueuePlaces(bool shadow, uint count) {
  return shadow ? atomicAdd(control.counts.z, count) : atomicAdd(control.counts.y, count);
}

// Appends `slot` to queue `queue` where `append` (the shadow queue with `shadow`). With
// subgroup arithmetic one atomic per subgroup reserves the subgroup's places (every
// invocation of the pass must come here, appending or not); otherwise one per path.
void appendToQueue(uint queue, bool shadow, uint slot, bool append) {
#ifdef MG_SUBGROUP_RAY_COUNT
  uint wanted = append ? 1u : 0u;
  uint total = subgroupAdd(wanted);
  uint offset = subgroupExclusiveAdd(wanted);
  uint base = 0u;
  if (subgroupElect() && total > 0u) base = reserveQueuePlaces(shadow, total);
  base = subgroupAdd(base);  // only the elected invocation holds a non-zero base
  if (append) pathQueues[queueIndex(queue, base + offset)] = slot;
#else
  if (append) pathQueues[queueIndex(queue, reserveQueuePlaces(shadow, 1u))] = slot;
#endif
}

// The Light Path state of a path's ray (kFieldPathState; the camera's where no graph reads it)
// and with Filter Glossy its minRayPdf (kFieldMinRayPdf).
PathState loadPathState(uint slot) {
#ifndef MG_OMIT_PATH_INPUTS
  ivec4 bits = floatBitsToInt(pathState[fieldIndex(kFieldPathState, slot)]);
  PathState path;
  path.ray = bits.x & 15;  // the ray's kind, and above it the transmission depth
  path.transmissionDepth = bits.x >> 4;
  path.depth = bits.y;
  path.diffuseDepth = bits.z;
  path.glossyDepth = bits.w;
#ifdef MG_WAVEFRONT_MIN_RAY_PDF_FIELD
  path.minRayPdf = pathState[fieldIndex(kFieldMinRayPdf, slot)].x;
#endif
  return path;
#elif defined(MG_WAVEFRONT_MIN_RAY_PDF_FIELD)
  PathState path = cameraPathState();
  path.minRayPdf = pathState[fieldIndex(kFieldMinRayPdf, slot)].x;
  return path;
#else
  return cameraPathState();
#endif
}

// The state a light point's emitter sees (lightSamplePathState of the vertex's), in one word
// beside the shadow ray's direction: the shade pass has stored the next ray's state in
// kFieldPathState by the time the light points' material pass runs. Each depth takes 8 bits
// and stops at 255 (the megakernel's does not: a difference past --bounces 255 only).
uint packLightPathState(PathState vertex) {
  PathState light = lightSamplePathState(vertex);
  return uint(min(light.depth, 255)) | (uint(min(light.diffuseDepth, 255)) << 8u) |
         (uint(min(light.glossyDepth, 255)) << 16u) |
         (uint(min(light.transmissionDepth, 255)) << 24u);
}
PathState unpackLightPathState(uint bits) {
  PathState light;
  light.ray = kPathRayLightSample;
  light.depth = int(bits & 0xFFu);
  light.diffuseDepth = int((bits >> 8u) & 0xFFu);
  light.glossyDepth = int((bits >> 16u) & 0xFFu);
  light.transmissionDepth = int(bits >> 24u);
  return light;
}

// Keeps the path state of a path's next ray (loadPathState's fields) for the next bounce's
// passes.
void storePathState(uint slot, PathState path) {
#ifndef MG_OMIT_PATH_INPUTS
  pathState[fieldIndex(kFieldPathState, slot)] =
      intBitsToFloat(ivec4(path.ray | (path.transmissionDepth << 4), path.depth,
                           path.diffuseDepth, path.glossyDepth));
#endif
#ifdef MG_WAVEFRONT_MIN_RAY_PDF_FIELD
  pathState[fieldIndex(kFieldMinRayPdf, slot)].x = path.minRayPdf;
#endif
}

#ifdef MG_WAVEFRONT_TRACED_INPUTS
// Adds an invocation's traced rays to the frame's count, as the megakernel counts them: with
// subgroup arithmetic one atomic per subgroup, so every invocation of it must call this.
void countTracedRays(uint rays) {
#ifdef MG_SUBGROUP_RAY_COUNT
  uint subgroupRays = subgroupAdd(rays);
  if (subgroupElect() && subgroupRays > 0u) atomicAdd(counters.rays, subgroupRays);
#else
  if (rays > 0u) atomicAdd(counters.rays, rays);
#endif
}
#endif

// The sample whose numbers this round's path vertex draws, as the megakernel's: with
// --shared-primary the camera ray is traced and its hit evaluated once, in the pixel's first
// path, whose numbers are round 0's.
uint vertexSampleIndex() {
  return sampleIndexOf(push.step.y == 0u && sharesPrimaryRay() ? 0u : push.step.x);
}

// The path vertex's word at slot's hit (setClosureSeed), as the megakernel draws it.
void setVertexClosureSeed(inout MaterialInputs inputs, uint slot) {
#ifndef MG_OMIT_PATH_INPUTS
  setClosureSeed(inputs, pixelOfSlot(slot), vertexSampleIndex(), push.step.y + 1u,
                 frame.image.w);
#endif
}

// The surface a live path's traced hit lies on (its ray, cone and hit from the path state),
// as the megakernel's loop body builds it: the material passes and the shade pass both
// start from here.
SurfaceHit surfaceOfPath(uint slot, out vec3 origin, out vec3 direction, out RayCone cone) {
  vec4 originField = pathState[fieldIndex(kFieldOrigin, slot)];
  vec4 directionField = pathState[fieldIndex(kFieldDirection, slot)];
  origin = originField.xyz;
  direction = directionField.xyz;
  uvec4 hitBits = floatBitsToUint(pathState[fieldIndex(kFieldHit, slot)]);
  HitInfo hit;
  hit.instanceIndex = hitBits.x;
  hit.primitiveIndex = hitBits.y;
  hit.barycentrics = uintBitsToFloat(hitBits.zw);
  hit.t = pathState[fieldIndex(kFieldRadiance, slot)].w;
  cone.width = originField.w;
  cone.spread = directionField.w;
  SurfaceHit s = surfaceAt(hit, origin, direction, cone);
  setPathInputs(s.inputs, loadPathState(slot), hit.t);
  setVertexClosureSeed(s.inputs, slot);
  return s;
}

#ifndef MG_MATERIAL_FLOOR
// The material bin of a live path's hit (one bin per distinct graph; the host's
// MG_MATERIAL_BIN_OF maps scene material ids to bins); kNoBin for a miss, or for a material
// id past the scene's, which the shade pass gives the default outputs (as the switch does).
const uint kNoBin = 0xffffffffu;
// A bin's records after WavefrontControl: its material pass's dispatch arguments (w: the
// frame's hits), its hits (count, first place, scatter cursor, batch) and its queued tiles
// (count, first place, scatter cursor, batch).
const uint kBinRecords = 3u;
const uint kBinOfMaterial[MG_MATERIAL_COUNT] = MG_MATERIAL_BIN_OF;
#ifdef MG_WAVEFRONT_TRACED_FIELD
// Per bin, whether its graph reads a traced input (the host's MG_MATERIAL_BIN_TRACED).
const bool kBinTracesInputs[MG_MATERIAL_BIN_COUNT] = MG_MATERIAL_BIN_TRACED;
#endif

// The scene material of a live path's hit, from its instance (no surface built).
uint materialOfPath(uint slot) {
  return instances[floatBitsToUint(pathState[fieldIndex(kFieldHit, slot)].x)].ids.y;
}

uint binOfPath(uint slot) {
  if (pathState[fieldIndex(kFieldRadiance, slot)].w < 0.0) return kNoBin;
  uint materialId = materialOfPath(slot);
  return materialId < uint(MG_MATERIAL_COUNT) ? kBinOfMaterial[materialId] : kNoBin;
}

// The binning and material passes after the shadow pass bin and evaluate light samples'
// points (push.chunk.w's kWavefrontLightPoints): the shadow pass's unblocked samples of
// emitters whose emission is their graph's, queued in the bounce's spent live queue.
bool binsLightPoints() {
#ifdef MG_NEE_EVALUATES_EMISSION
  return (push.chunk.w & kWavefrontLightPoints) != 0u;
#else
  return false;
#endif
}

// The paths the binning passes bin: the live queue's, or the light points'.
uint binnedCount() {
  return binsLightPoints() ? control.counts.w : control.counts.x;
}

// The bin whose material pass must evaluate a live path's hit: with the texel cache what
// the lookup pass left (kNoBin after a cache hit), otherwise the hit's own; for a light
// point its emitter's.
uint binToEvaluate(uint slot) {
#ifdef MG_NEE_EVALUATES_EMISSION
  if (binsLightPoints()) {
    uint materialId = instances[floatBitsToUint(pathState[fieldIndex(kFieldLightHit, slot)].x)].ids.y;
    return materialId < uint(MG_MATERIAL_COUNT) ? kBinOfMaterial[materialId] : kNoBin;
  }
#endif
#ifdef MG_WAVEFRONT_CACHE
  return floatBitsToUint(pathState[fieldIndex(kFieldMaterialRest, slot)].w);
#else
  return binOfPath(slot);
#endif
}
#endif

#ifdef MG_WAVEFRONT_CACHE
// Whether bounce `bounce`'s hits use the cache: with MG_CACHE_SECONDARY_ONLY the camera rays'
// hits evaluate their graphs directly (§6.1, Fig. 6.6), as in the megakernel.
bool cacheTakesBounce(uint bounce) {
#ifdef MG_CACHE_SECONDARY_ONLY
  return bounce != 0u;
#else
  return true;
#endif
}
#endif

#if !defined(MG_MATERIAL_FLOOR) && \
    (defined(MG_WAVEFRONT_MATERIAL) || defined(MG_WAVEFRONT_SHADE) || defined(MG_WAVEFRONT_LOOKUP))
// The material's outputs at a path's hit, from the material pass to the shade pass.
void storeMaterialOutputs(uint slot, MaterialOutputs m) {
  pathState[fieldIndex(kFieldMaterialBase, slot)] = vec4(m.baseColor, m.metallic);
  pathState[fieldIndex(kFieldMaterialNormal, slot)] = vec4(m.normal, m.roughness);
  pathState[fieldIndex(kFieldMaterialEmission, slot)] = vec4(m.emission, m.specular);
  pathState[fieldIndex(kFieldMaterialRest, slot)] =
      vec4(m.specularTint, m.cyclesPrincipled, m.opacity, 0.0);
#ifdef MG_WAVEFRONT_LOBE_FIELD
  // Lobes past the count are stored with kind 0, which loadMaterialOutputs counts to.
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    vec4 weight = i < m.lobeCount ? m.lobeWeight[i] : vec4(0.0);
    pathState[fieldIndex(kFieldLobes + 2u * uint(i), slot)] = weight;
    pathState[fieldIndex(kFieldLobes + 2u * uint(i) + 1u, slot)] = m.lobeParameters[i];
  }
#endif
}

MaterialOutputs loadMaterialOutputs(uint slot, SurfaceHit s) {
  MaterialOutputs m = mg_defaultMaterialOutputs(s.inputs);
  if (s.materialId >= uint(MG_MATERIAL_COUNT)) return m;  // no bin evaluated it
  vec4 base = pathState[fieldIndex(kFieldMaterialBase, slot)];
  vec4 normal = pathState[fieldIndex(kFieldMaterialNormal, slot)];
  vec4 emission = pathState[fieldIndex(kFieldMaterialEmission, slot)];
  vec4 rest = pathState[fieldIndex(kFieldMaterialRest, slot)];
  m.baseColor = base.rgb;
  m.metallic = base.w;
  m.normal = normal.xyz;
  m.roughness = normal.w;
  m.emission = emission.rgb;
  m.specular = emission.w;
  m.specularTint = rest.x;
  m.cyclesPrincipled = rest.y;
  m.opacity = rest.z;
#ifdef MG_WAVEFRONT_LOBE_FIELD
  m.lobeCount = 0;
  for (int i = 0; i < MG_MAX_LOBES; ++i) {
    m.lobeWeight[i] = pathState[fieldIndex(kFieldLobes + 2u * uint(i), slot)];
    m.lobeParameters[i] = pathState[fieldIndex(kFieldLobes + 2u * uint(i) + 1u, slot)];
    if (m.lobeWeight[i].w != 0.0) m.lobeCount = i + 1;
  }
#endif
  return m;
}
#endif

#if defined(MG_WAVEFRONT_CUT_FIELD) && \
    (defined(MG_WAVEFRONT_MATERIAL) || defined(MG_WAVEFRONT_SHADE) || defined(MG_WAVEFRONT_LOOKUP))
// A cut's `width` values at a path's hit, from the lookup or material pass to the shade pass.
void storeCutValues(uint slot, float values[MG_CACHE_VALUES], uint width) {
  for (uint f = 0u; f < uint(MG_WAVEFRONT_CUT_FIELDS); ++f) {
    if (4u * f >= width) break;
    vec4 field = vec4(0.0);
    for (uint c = 0u; c < 4u; ++c)
      if (4u * f + c < uint(MG_CACHE_VALUES)) field[c] = values[4u * f + c];
    pathState[fieldIndex(kFieldCut + f, slot)] = field;
  }
}

void loadCutValues(uint slot, uint width, out float values[MG_CACHE_VALUES]) {
  for (uint k = 0u; k < uint(MG_CACHE_VALUES); ++k) values[k] = 0.0;
  for (uint f = 0u; f < uint(MG_WAVEFRONT_CUT_FIELDS); ++f) {
    if (4u * f >= width) break;
    vec4 field = pathState[fieldIndex(kFieldCut + f, slot)];
    for (uint c = 0u; c < 4u; ++c)
      if (4u * f + c < uint(MG_CACHE_VALUES)) values[4u * f + c] = field[c];
  }
}
#endif

#if defined(MG_WAVEFRONT_BIN_COUNT) || defined(MG_WAVEFRONT_BIN_SCATTER)
// Adds 1 for each invocation with `adds` to a bin record's counter (x, the count, or with
// `cursor` z, the scatter's cursor) and returns the value before the invocation's own 1. One
// atomic per bin and path made the binning passes the wavefront's slowest without a cache
// (35.7 ms a frame of 96.7 on the classroom, H200, 1080p, P = 6, L = 4: 88 bins, 12 M paths
// a bounce contending for them). With subgroup arithmetic there is one atomic per distinct
// record in the subgroup: each round takes the smallest record still pending, its
// invocations' places are a prefix sum on one reservation (every invocation of the pass must
// come here, adding or not, as for appendToQueue); coherent bins (a pixel block's hits on one
// material) cost one round. On the H200 the binning passes went from 35.7 to 9.9 ms a frame
// (every 10th camera before, the first 40 after; the floor 47.6 and 46.9 ms on those frames).
uint addToBinRecord(uint record, bool cursor, bool adds) {
#ifdef MG_SUBGROUP_RAY_COUNT
  uint place = 0u;
  bool pending = adds;
  while (subgroupAdd(pending ? 1u : 0u) != 0u) {  // arithmetic only: no vote needed
    uint chosen = subgroupMin(pending ? record : 0xFFFFFFFFu);
    uint mine = pending && record == chosen ? 1u : 0u;
    uint count = subgroupAdd(mine);
    uint rank = subgroupExclusiveAdd(mine);
    uint base = 0u;
    if (subgroupElect()) {
      base = cursor ? atomicAdd(materialBins[chosen].z, count)
                    : atomicAdd(materialBins[chosen].x, count);
    }
    base = subgroupAdd(base);  // only the elected invocation holds a non-zero base
    if (mine != 0u) {
      place = base + rank;
      pending = false;
    }
  }
  return place;
#else
  if (!adds) return 0u;
  return cursor ? atomicAdd(materialBins[record].z, 1u) : atomicAdd(materialBins[record].x, 1u);
#endif
}
#endif

#if defined(MG_WAVEFRONT_GENERATE)
// Camera rays of round push.step.x: path `round` of every pixel of the chunk, one slot per
// pixel.
void main() {
  uint slot = invocationIndex();
  uint slots = push.chunk.z;
  if (slot == 0u) {
    control.counts = uvec4(slots, 0u, 0u, 0u);
    control.liveGroups = uvec4(workgroupsFor(slots), 1u, 1u, 0u);
    control.liveLaunch = uvec4(slots, 1u, 1u, 0u);
    // With --shared-primary the later rounds' camera rays are round 0's hits, not traced.
    bool traced = !sharesPrimaryRay() || push.step.x == 0u;
    if (traced) atomicAdd(counters.rays, slots);
  }
  if (slot >= slots) return;
  uint pixelIndex = pixelOfSlot(slot);
  uvec2 pixel = uvec2(pixelIndex % frame.image.x, pixelIndex / frame.image.x);
  Rng rng = rngForPathVertex(pixelIndex, sampleIndexOf(push.step.x), 0u, frame.image.w);
  // --shared-primary (thesis §5.1): every round's camera ray through the pixel centre, traced
  // once for the P paths (round 0; the trace pass keeps its hit for the others), as the
  // megakernel traces it.
  bool sharedPrimary = sharesPrimaryRay();
  vec3 origin, direction;
  primaryRay(pixel, sharedPrimary ? vec2(0.5) : rngNext2(rng), origin, direction);
  pathState[fieldIndex(kFieldOrigin, slot)] = vec4(origin, 0.0);
  pathState[fieldIndex(kFieldDirection, slot)] = vec4(direction, frame.cameraPosition.w);
  pathState[fieldIndex(kFieldThroughput, slot)] = vec4(1.0, 1.0, 1.0, 0.0);
  pathState[fieldIndex(kFieldRadiance, slot)] = vec4(0.0);
  storePathState(slot, cameraPathState());
#ifdef MG_DEBUG_CACHE_MISSES
  // The pixel's "a path missed the cache" flag (kFieldPixelSum's w) starts each frame clear.
  if (push.step.x == 0u) pathState[fieldIndex(kFieldPixelSum, slot)] = vec4(0.0);
#endif
  pathQueues[queueIndex(0u, slot)] = slot;
}

#elif defined(MG_WAVEFRONT_TRACE)
#ifdef MG_HIT_FEEDBACK
// What the ray this pass traces for `slot` counts in LiPaC's feedback: what the megakernel's
// tracePixel counts for the same ray (0 in a frame that does not count, push.chunk.w).
// With --shared-primary the camera ray is traced once, in round 0, and counted there with the
// pixel's weight, as the megakernel counts its one trace of it.
uint traceFeedbackWeight(uint slot) {
  if ((push.chunk.w & kWavefrontCountsHits) == 0u) return 0u;
  uint pixelIndex = pixelOfSlot(slot);
  uint weight = hitFeedbackWeight(uvec2(pixelIndex % frame.image.x, pixelIndex / frame.image.x));
  uint round = push.step.x;
  if (push.step.y == 0u && (frame.path.z & kFlagSharedPrimaryRay) != 0u)
    return round == 0u ? weight : 0u;
  return pathFeedbackWeight(round, max(frame.path.x, 1u), weight);
}
#endif

// The closest hit of every live path; camera rays skip lights' quads, as in the megakernel.
// With --shared-primary round 0 traces the pixel's camera ray and keeps its hit, which the
// later rounds take instead of tracing the same ray again. With LiPaC's feedback the ray is
// counted after its trace (every invocation reaches the tally: with subgroup arithmetic it is
// one atomic per subgroup).
void main() {
  uint i = invocationIndex();
  if (i < control.counts.x) {
    uint slot = pathQueues[queueIndex(push.step.z, i)];
    vec4 originField = pathState[fieldIndex(kFieldOrigin, slot)];  // w: the ray cone's width
    vec4 directionField = pathState[fieldIndex(kFieldDirection, slot)];  // w: its spread
    vec3 origin = originField.xyz;
    vec3 direction = directionField.xyz;
    HitInfo hit;
#ifdef MG_WAVEFRONT_PRIMARY_FIELD
    bool sharedCameraRay = push.step.y == 0u && (frame.path.z & kFlagSharedPrimaryRay) != 0u;
    if (sharedCameraRay && push.step.x != 0u) {
      uvec4 hitBits = floatBitsToUint(pathState[fieldIndex(kFieldPrimaryHit, slot)]);
      hit.instanceIndex = hitBits.x;
      hit.primitiveIndex = hitBits.y;
      hit.barycentrics = uintBitsToFloat(hitBits.zw);
      hit.t = pathState[fieldIndex(kFieldPrimaryT, slot)].x;
    } else
#endif
    {
#ifdef MG_STOCHASTIC_OPACITY
      // Through surfaces by their opacity (stochastic_opacity.glsl), drawing from the key of
      // the vertex the ray finds, as the megakernel's traceCounted does: with --shared-primary
      // the camera ray's from round 0's sample. The segments past the first count as rays.
      uint vertexKey =
          rngForPathVertex(pixelOfSlot(slot), vertexSampleIndex(), push.step.y + 1u, frame.image.w)
              .key;
      uint crossings = 0u;
      hit = traceThroughOpacity(origin, direction, kRayTMax,
                                push.step.y == 0u ? kRayMaskNoLightQuads : kRayMaskAll,
                                loadPathState(slot), vertexKey, crossings);
      if (crossings > 0u) atomicAdd(counters.rays, crossings);
#else
      hit = traceClosest(origin, direction, kRayTMax,
                         push.step.y == 0u ? kRayMaskNoLightQuads : kRayMaskAll);
#endif
    }
    vec4 hitField = uintBitsToFloat(
        uvec4(hit.instanceIndex, hit.primitiveIndex, floatBitsToUint(hit.barycentrics)));
    pathState[fieldIndex(kFieldHit, slot)] = hitField;
    pathState[fieldIndex(kFieldRadiance, slot)].w = hit.t;
#ifdef MG_WAVEFRONT_PRIMARY_FIELD
    if (sharedCameraRay && push.step.x == 0u) {
      pathState[fieldIndex(kFieldPrimaryHit, slot)] = hitField;
      pathState[fieldIndex(kFieldPrimaryT, slot)] = vec4(hit.t, 0.0, 0.0, 0.0);
    }
#endif
#ifdef MG_HIT_FEEDBACK
    uint weight = traceFeedbackWeight(slot);
    countHitFeedback(origin, direction, hit, weight);
    // The mesh LODs' footprint (seeds/001 §3.1.1): the cone's width at the hit, as the
    // megakernel's surfaceAt measures it (eq. 2.10), from the cone the path state carries, so
    // both architectures choose the same LODs.
    if (weight != 0u && hit.t >= 0.0) {
      RayCone cone;
      cone.width = originField.w;
      cone.spread = directionField.w;
      bufferHitFootprint(hit.instanceIndex, rayConeWidthAt(cone, hit.t));
    }
    flushHitFeedback();
#endif
  }
#ifdef MG_HIT_FEEDBACK
  addHitFeedbackTally();
#endif
}

#elif defined(MG_WAVEFRONT_LOOKUP)
// The texel cache's lookup (thesis §5.3) of every live hit, as the megakernel's
// evaluateMaterialCached begins: a cache hit's values become the hit's material outputs (the
// members its material does not cache as mg_defaultMaterialOutputs leaves them); a cache
// miss, a material the cache does not take or a hit without usable texture coordinates is
// left to its bin's material pass. The bin goes into the path state for the binning passes
// (kNoBin: nothing to evaluate, a ray that missed the scene too).
void main() {
  uint i = invocationIndex();
  if (i < control.counts.x) {
    uint slot = pathQueues[queueIndex(push.step.z, i)];
    uint bin = binOfPath(slot);
    // Whole uv-only materials are looked up here, whose found hits then need no material
    // pass; the material id comes from the hit's instance, so the surface is built for those
    // alone. So are materials keyed by their cut whose rest the shade pass runs
    // (MG_WAVEFRONT_CUT_FIELD, mg_materialCutInfo's w): a found entry's values go to the shade
    // pass; a missing one is left to its material pass, which reads the entry again (and
    // counts that lookup), evaluates the cut and inserts it. Every material with a filtered
    // read, which blends (or picks among) several entries, reads in its material pass.
    uvec4 info = uvec4(0u);
    uvec4 cut = uvec4(0u);
#ifndef MG_CACHE_FILTER
    if (bin != kNoBin) {
      uint materialId = materialOfPath(slot);
      info = cacheInfoOf(materialId);
#ifdef MG_WAVEFRONT_CUT_FIELD
      if (info.x == 0u) cut = cutInfoOf(materialId);
#endif
    }
#endif
    bool cutLookup = cut.w != 0u;
    if ((info.x != 0u || cutLookup) && frame.cache.x != 0u && cacheTakesBounce(push.step.y)) {
      vec3 origin, direction;
      RayCone cone;
      SurfaceHit s = surfaceOfPath(slot, origin, direction, cone);
#ifdef MG_WAVEFRONT_CUT_FIELD
      if (cutLookup) {
        CacheKey cutKey;
        MaterialInputs keyInputs;  // unread here: a miss's material pass evaluates the cut
        float cutValues[MG_CACHE_VALUES];
        if (cacheCutKeyFor(info, cut, s.object, s.inputs, cutKey, keyInputs) &&
            cacheRead(cutKey, cutValues)) {
          g_cacheLookups += 1u;
          g_cacheHits += 1u;
          storeCutValues(slot, cutValues, cut.y);
          bin = kNoBin;
        }
      } else
#endif
      {
        // The texel's key, or (§5.4) the hit's tile, whose read filters its texels.
#ifdef MG_WAVEFRONT_TILES
        TileRequest request;
        bool cached = tileRequestFor(info, s.inputs, request);
#else
        CacheKey request;
        bool cached = cacheKeyFor(info, s.inputs, request);
#endif
        if (cached) {
          g_cacheLookups += 1u;
          float values[MG_CACHE_VALUES];
          if (cacheRead(request, values)) {
            g_cacheHits += 1u;
            storeMaterialOutputs(slot, cacheUnpack(info.x, values, s.inputs));
            bin = kNoBin;
          } else {
            g_cacheMisses += 1u;
#ifdef MG_DEBUG_CACHE_MISSES
            pathState[fieldIndex(kFieldPixelSum, slot)].w = 1.0;  // the pixel's flag (finish)
#endif
#ifdef MG_WAVEFRONT_TILES
            // Queued once a frame (the tile log) for its bin's material pass to compute.
            tileEnqueue(s.materialId, request);
#endif
          }
        }
      }
    }
    pathState[fieldIndex(kFieldMaterialRest, slot)].w = uintBitsToFloat(bin);
  }
  cacheStampReads();  // with subgroup arithmetic, every invocation of the subgroup
  cacheAddCounts();
#ifdef MG_WAVEFRONT_TILES
  tileAddCounts();
#endif
}

#elif defined(MG_WAVEFRONT_BIN_COUNT)
// Counts the live hits of each material bin (a miss is shaded without a material), and with
// the tile cache the bounce's queued tiles of each (no more than its live paths: each came
// from one's lookup).
void main() {
  uint i = invocationIndex();
#ifdef MG_WAVEFRONT_TILES
  bool tile = i < queuedTiles();
  addToBinRecord(tile ? kBinRecords * kBinOfMaterial[tileQueue[i].materialId] + 2u : 0u, false,
                 tile);
#endif
  uint bin = i < binnedCount() ? binToEvaluate(pathQueues[queueIndex(push.step.z, i)]) : kNoBin;
  addToBinRecord(kBinRecords * bin + 1u, false, bin != kNoBin);
}

#elif defined(MG_WAVEFRONT_BIN_OFFSETS)
// The bins' counts into an exclusive prefix sum (each bin's first place in the material-
// sorted queue) and each bin's material-pass arguments; the counters start again from 0 (the
// host zeroes the records before a frame). The arguments' w sums the bin's hits over the
// frame, for FrameStats. A few hundred bins at most: one invocation walks them.
// With the tile cache each bin's queued tiles get their segment of the sorted tile list too,
// and its material pass one invocation more per texel of them.
// With traced inputs the bins whose graph reads one come first (a sweep over them, then one
// over the others), so their hits are the sorted queue's first places: the traced-inputs
// pass runs over that prefix alone, with no bin it need not trace for.
#ifdef MG_WAVEFRONT_TRACED_FIELD
const uint kOffsetSweeps = 2u;
uint offsetSweepOf(uint bin) {
  return kBinTracesInputs[bin] ? 0u : 1u;
}
#else
const uint kOffsetSweeps = 1u;
uint offsetSweepOf(uint bin) {
  return 0u;
}
#endif

void main() {
  if (invocationIndex() != 0u) return;
  uint offset = 0u;
  uint tileOffset = 0u;
  for (uint sweep = 0u; sweep < kOffsetSweeps; ++sweep) {
    for (uint bin = 0u; bin < uint(MG_MATERIAL_BIN_COUNT); ++bin) {
      if (offsetSweepOf(bin) != sweep) continue;
      uint count = materialBins[kBinRecords * bin + 1u].x;
      uint tiles = materialBins[kBinRecords * bin + 2u].x;
      uint frameHits = materialBins[kBinRecords * bin].w + count;
      materialBins[kBinRecords * bin] =
          uvec4(materialWorkgroupsFor(count + tiles * kTileTexelsOrZero), 1u, 1u, frameHits);
      materialBins[kBinRecords * bin + 1u] = uvec4(0u, offset, offset, count);
      materialBins[kBinRecords * bin + 2u] = uvec4(0u, tileOffset, tileOffset, tiles);
      offset += count;
      tileOffset += tiles;
    }
#ifdef MG_WAVEFRONT_TRACED_FIELD
    // The hits of the bins that read a traced input: the traced-inputs pass's arguments (the
    // light points' binning writes them too, after that pass has run for the bounce).
    if (sweep == 0u) {
      control.tracedGroups = uvec4(workgroupsFor(offset), 1u, 1u, 0u);
      control.tracedLaunch = uvec4(offset, 1u, 1u, 0u);
    }
#endif
  }
}

#elif defined(MG_WAVEFRONT_BIN_SCATTER)
// The live hits' slots into the material-sorted queue, each at its bin's cursor; with the tile
// cache the queued tiles' slots into the sorted tile list likewise.
void main() {
  uint i = invocationIndex();
#ifdef MG_WAVEFRONT_TILES
  bool tile = i < queuedTiles();
  uint tilePlace = addToBinRecord(
      tile ? kBinRecords * kBinOfMaterial[tileQueue[i].materialId] + 2u : 0u, true, tile);
  if (tile) pathQueues[queueIndex(4u, tilePlace)] = i;
#endif
  uint slot = i < binnedCount() ? pathQueues[queueIndex(push.step.z, i)] : 0u;
  uint bin = i < binnedCount() ? binToEvaluate(slot) : kNoBin;
  uint place = addToBinRecord(kBinRecords * bin + 1u, true, bin != kNoBin);
  if (bin != kNoBin) pathQueues[queueIndex(3u, place)] = slot;
}

#elif defined(MG_WAVEFRONT_TRACED_INPUTS) && defined(MG_INTEGRATOR_AO)
// The AO integrator (--integrator ao): its rounds are generate, trace, this pass and finish.
// Each live path's camera-ray hit gets the megakernel's estimate
// (ambientOcclusionIntegratorAt), a miss 1 (nothing occludes the sky), as the path's
// radiance, which the finish pass averages over the rounds. Every AO ray is counted.
void main() {
  uint i = invocationIndex();
  uint rays = 0u;
  if (i < control.counts.x) {
    uint slot = pathQueues[queueIndex(push.step.z, i)];
    float unoccluded = 1.0;
    if (pathState[fieldIndex(kFieldRadiance, slot)].w >= 0.0) {
      vec3 origin, direction;
      RayCone cone;
      SurfaceHit s = surfaceOfPath(slot, origin, direction, cone);
      unoccluded =
          ambientOcclusionIntegratorAt(s, pixelOfSlot(slot), sampleIndexOf(push.step.x), rays);
    }
    pathState[fieldIndex(kFieldRadiance, slot)] = vec4(vec3(unoccluded), 0.0);
  }
  countTracedRays(rays);  // every invocation comes here
}

#elif defined(MG_WAVEFRONT_TRACED_INPUTS)
// The traced inputs (docs/design/traced-inputs.md) of the hits whose material reads one: the
// material-sorted queue's first control.tracedLaunch.x places, which the bin offsets pass
// gave those materials' bins. Each hit's surface is built as its material pass builds it, and
// the megakernel's setTracedInputs traces the Ambient Occlusion and Bevel rays from it with
// the megakernel's random numbers for this path vertex (tracedInputsRng), so at one seed both
// architectures trace the same rays. The results go into the path state for the material
// pass. With --shared-primary the camera ray's hit is the same surface in every round, and
// the megakernel evaluates its material once, in the pixel's first path: its numbers are
// round 0's here. Every traced ray is counted, as the megakernel counts them.
void main() {
  uint i = invocationIndex();
  uint rays = 0u;
  if (i < control.tracedLaunch.x) {
    uint slot = pathQueues[queueIndex(3u, i)];
    vec3 origin, direction;
    RayCone cone;
    SurfaceHit s = surfaceOfPath(slot, origin, direction, cone);
    Rng rng = tracedInputsRng(pixelOfSlot(slot), vertexSampleIndex(), push.step.y + 1u,
                              frame.image.w);
    setTracedInputs(s, rng, rays);
    pathState[fieldIndex(kFieldTracedInputs, slot)] =
        vec4(s.inputs.bevelNormal, s.inputs.ambientOcclusion);
  }
  countTracedRays(rays);  // every invocation comes here
}

#elif defined(MG_WAVEFRONT_MATERIAL)

// One distinct graph over its bin's batch (bin push.step.w) of the material-sorted queue:
// the material inputs built from the hit as the megakernel builds them, the graph's outputs
// into the path state for the shade pass.
// With the tile cache the invocations past the bin's hits compute its queued tiles, one
// texel each (the deferred fill's tileFillTexel, with this graph): the last of a tile's
// texels to be stored publishes it, so the next bounce's lookups find it.
// The graph is called at one place in the pass (with a filtered or cut read of the texel
// cache, evaluateMaterialCached's own calls besides): a driver inlines every call, so each
// call site would be a whole copy of the graph in the pipeline, and a cold start compiles
// one such pass per distinct graph. So an invocation first chooses what it evaluates (a
// queued tile's texel, a light point or its hit), then calls the graph, then chooses where
// the outputs go (docs/design/wavefront.md, "What a material pass holds").

// Whether this dispatch evaluates light points: compiled only into the passes of graphs that
// some emitter's light samples evaluate (MG_MATERIAL_LIGHT_POINTS, the host's, per graph);
// the other graphs' bins never hold a point.
bool evaluatesLightPoints() {
#ifdef MG_MATERIAL_LIGHT_POINTS
  return binsLightPoints();
#else
  return false;
#endif
}

// The surface a binned path's graph is evaluated at: its traced hit (surfaceOfPath's), or for
// a light point the sampled emitter point seen from its shading point along the shadow ray,
// with a zero cone, as the megakernel's sampleDirectLight evaluates it once its shadow ray is
// unblocked. One surfaceAt for both, so that the pass holds one copy of it.
SurfaceHit surfaceToEvaluate(uint slot, bool lightPoint) {
  vec4 hitField, originField, directionField;
  float t;
  PathState vertex;
#ifdef MG_MATERIAL_LIGHT_POINTS
  if (lightPoint) {
    hitField = pathState[fieldIndex(kFieldLightHit, slot)];
    vec4 lightOrigin = pathState[fieldIndex(kFieldLightOrigin, slot)];
    vec4 shadowDirection = pathState[fieldIndex(kFieldShadowDirection, slot)];
    originField = vec4(lightOrigin.xyz, 0.0);
    directionField = vec4(shadowDirection.xyz, 0.0);
    t = lightOrigin.w;
    vertex = unpackLightPathState(floatBitsToUint(shadowDirection.w));
  } else
#endif
  {
    hitField = pathState[fieldIndex(kFieldHit, slot)];
    originField = pathState[fieldIndex(kFieldOrigin, slot)];
    directionField = pathState[fieldIndex(kFieldDirection, slot)];
    t = pathState[fieldIndex(kFieldRadiance, slot)].w;
    vertex = loadPathState(slot);
  }
  uvec4 hitBits = floatBitsToUint(hitField);
  HitInfo hit;
  hit.instanceIndex = hitBits.x;
  hit.primitiveIndex = hitBits.y;
  hit.barycentrics = uintBitsToFloat(hitBits.zw);
  hit.t = t;
  RayCone cone;
  cone.width = originField.w;
  cone.spread = directionField.w;
  SurfaceHit s = surfaceAt(hit, originField.xyz, directionField.xyz, cone);
  setPathInputs(s.inputs, vertex, t);
  if (!lightPoint) setVertexClosureSeed(s.inputs, slot);
#ifdef MG_WAVEFRONT_TRACED_FIELD
  // A hit's traced inputs, as the traced-inputs pass left them for a material that reads
  // them; a light point keeps surfaceAt's 1 and shading normal, as the megakernel's
  // (sampleDirectLight traces nothing for an emitter's graph).
  if (!lightPoint) {
    bool ambientOcclusion = mg_materialAmbientOcclusion[s.materialId].y != 0u;
    bool bevel = mg_materialBevel[s.materialId].y != 0u;
    if (ambientOcclusion || bevel) {
      vec4 traced = pathState[fieldIndex(kFieldTracedInputs, slot)];
      if (ambientOcclusion) s.inputs.ambientOcclusion = traced.w;
      if (bevel) s.inputs.bevelNormal = traced.xyz;
    }
  }
#endif
  return s;
}

// Where an evaluation's outputs go: a hit's into the path state for the shade pass; a light
// point's emission scales its sample's contribution, added to the path's radiance.
void storeEvaluated(uint slot, bool lightPoint, MaterialOutputs m) {
#ifdef MG_MATERIAL_LIGHT_POINTS
  if (lightPoint) {
    vec3 contribution = pathState[fieldIndex(kFieldShadowContribution, slot)].rgb;
#ifdef MG_STOCHASTIC_OPACITY
    // The emitter's expected emission, alpha * E, as the megakernel's sampleDirectLight takes it.
    contribution *= clamp(m.opacity, 0.0, 1.0);
#endif
    pathState[fieldIndex(kFieldRadiance, slot)].rgb += contribution * m.emission;
    return;
  }
#endif
  storeMaterialOutputs(slot, m);
}

#if defined(MG_CACHE_CUT_PASS) && !defined(MG_CACHE_FILTER)
// The material pass of a graph keyed by its cut. The lookup pass handed the shade pass the
// values of the hits whose entry it found (a graph whose rest the shade pass runs,
// MG_MATERIAL_REST_IN_SHADE), so this pass sees the misses, the hits without a
// key (a bounce the cache does not take, no usable key) and light points: nearly every
// invocation evaluates the cut, side by side with its subgroup's others, so none gathers
// them (a shared-memory list would run a work group's cuts 32 at a time while its other
// subgroups wait: H100, 9.7 against 4.5 ms a frame). The cut's entry is read again under §5.3.4's check
// (an earlier work group of this pass may have inserted it), a missing one evaluated at its
// key's centre and inserted; a hit without a key (or, with `lightPoint`, a light point:
// evaluated without the cache, as the megakernel's) evaluates the cut at its own inputs. Then
// a hit's values go to the shade pass (MG_MATERIAL_REST_IN_SHADE), or the rest of the graph
// runs with the hit's own inputs: for a light point, and for a graph with a traced input,
// whose values this pass has. One copy of the graph: the cut, then the rest.
void materialPassThroughCut(uint slot, bool lightPoint) {
  SurfaceHit s = surfaceToEvaluate(slot, lightPoint);
  s.inputs.textureBase = MG_TEXTURE_BASE;  // as the switch's case sets it
  bool keyed = !lightPoint && cacheTakesBounce(push.step.y) && frame.cache.x != 0u;
  CacheKey key;
  MaterialInputs keyInputs;
  float values[MG_CACHE_VALUES];
  if (!cacheReadCut(cacheInfoOf(s.materialId), cutInfoOf(s.materialId), s.object, s.inputs,
                    keyed, key, keyInputs, values)) {
    evaluateMaterialCutSwitch(0u, keyInputs, values);
    if (keyed) cacheWrite(key, values);
  }
#ifdef MG_DEBUG_CACHE_MISSES
  if (g_cacheMissed) pathState[fieldIndex(kFieldPixelSum, slot)].w = 1.0;  // as the lookup's
#endif
#ifdef MG_MATERIAL_REST_IN_SHADE
  if (!lightPoint) {
    storeCutValues(slot, values, uint(MG_MATERIAL_CUT_WIDTH));
    return;
  }
#endif
#if !defined(MG_MATERIAL_REST_IN_SHADE) || defined(MG_MATERIAL_LIGHT_POINTS)
  MaterialOutputs m;
  evaluateMaterialRestSwitch(s.materialId, s.inputs, values, m);
  storeEvaluated(slot, lightPoint, m);
#endif
}
#endif

void main() {
  uvec4 bin = materialBins[kBinRecords * push.step.w + 1u];
  uint i = invocationIndex();
  const bool lightPoint = evaluatesLightPoints();
#if defined(MG_CACHE_CUT_PASS) && !defined(MG_CACHE_FILTER)
#if defined(MG_NEE_EVALUATES_EMISSION) && !defined(MG_MATERIAL_LIGHT_POINTS)
  if (binsLightPoints()) return;  // no emitter's light samples evaluate this graph
#endif
  if (i < bin.w) materialPassThroughCut(pathQueues[queueIndex(3u, bin.y + i)], lightPoint);
  cacheAddCounts();
  return;
#endif
  uint slot = 0u;
  SurfaceHit s;
#ifdef MG_WAVEFRONT_TILES
  bool tileTexel = i >= bin.w;
  uint queueSlot = 0u;
  uint texel = 0u;
  TileFillItem item;
  if (tileTexel) {
    uvec4 tiles = materialBins[kBinRecords * push.step.w + 2u];
    uint tile = (i - bin.w) / kTileTexels;
    if (tile >= tiles.w) return;
    texel = (i - bin.w) % kTileTexels;
    queueSlot = pathQueues[queueIndex(4u, tiles.y + tile)];
    item = tileQueue[queueSlot];
    s.inputs = tileFillInputs(item, texel);
  } else
#else
  if (i >= bin.w) return;
#endif
  {
#if defined(MG_NEE_EVALUATES_EMISSION) && !defined(MG_MATERIAL_LIGHT_POINTS)
    if (binsLightPoints()) return;  // no emitter's light samples evaluate this graph
#endif
    slot = pathQueues[queueIndex(3u, bin.y + i)];
    s = surfaceToEvaluate(slot, lightPoint);
  }
  s.inputs.textureBase = MG_TEXTURE_BASE;  // as the switch's case sets it
  MaterialOutputs m;
#ifdef MG_CACHE_TEXEL
#if defined(MG_EVALUATE_MATERIAL_CUT) && !defined(MG_CACHE_FILTER)
  return;  // not reached: materialPassThroughCut evaluated the bin
#elif defined(MG_EVALUATE_MATERIAL_CUT)
  // A graph keyed by its cut and read with a filter, in place as the megakernel's
  // evaluateMaterialThroughCut (the lookup pass left every such hit to this pass): the
  // entries around the hit, a missing one evaluated at its key's centre and inserted, then
  // the rest of the graph with the hit's own inputs. The entries are read under §5.3.4's
  // check, since this pass inserts. A bounce the cache does not take, and a light point (as
  // the megakernel's, without the cache), run the cut at their own inputs: the pass holds
  // one copy of its graph either way (MG_CACHE_CUT_PASS).
  bool keyed = !lightPoint && cacheTakesBounce(push.step.y);
  // The stochastic filter's picks, as the megakernel seeds them for this path vertex.
  if (keyed)
    cacheSeedFilterPicks(pixelOfSlot(slot), sampleIndexOf(push.step.x), push.step.y + 1u,
                         frame.image.w);
  evaluateMaterialThroughCut(s.materialId, cutInfoOf(s.materialId), s.object, s.inputs, keyed,
                             m);
#ifdef MG_DEBUG_CACHE_MISSES
  if (g_cacheMissed) pathState[fieldIndex(kFieldPixelSum, slot)].w = 1.0;  // as the lookup's
#endif
  cacheAddCounts();
  storeEvaluated(slot, lightPoint, m);
  return;
#elif defined(MG_CACHE_FILTER) && defined(MG_MATERIAL_CACHEABLE)
  // A whole uv-only graph read with a filter, in place as the megakernel's
  // evaluateMaterialCached: the entries around the hit, each missing one evaluated at its
  // centre and inserted (the lookup pass reads only unfiltered). A light point is evaluated
  // without the cache, as the megakernel's.
  if (!lightPoint && cacheTakesBounce(push.step.y)) {
    // The stochastic filter's picks, as the megakernel seeds them for this path vertex.
    cacheSeedFilterPicks(pixelOfSlot(slot), sampleIndexOf(push.step.x), push.step.y + 1u,
                         frame.image.w);
    evaluateMaterialCached(s.materialId, s.object, s.inputs, m);
#ifdef MG_DEBUG_CACHE_MISSES
    if (g_cacheMissed) pathState[fieldIndex(kFieldPixelSum, slot)].w = 1.0;  // as the lookup's
#endif
  } else {
    MG_EVALUATE_MATERIAL(s.inputs, m);
  }
  cacheAddCounts();
  storeEvaluated(slot, lightPoint, m);
  return;
#endif
#ifdef MG_MATERIAL_CACHEABLE
  uvec4 info = cacheInfoOf(s.materialId);
  // A miss of the lookup pass: evaluated (at its texel's centre with MG_CACHE_SNAP_UV) and
  // inserted, as evaluateMaterialCached does after its read; the same key, recomputed. A
  // light point is evaluated without the cache, as the megakernel's.
  CacheKey key;
  bool insert = !lightPoint && cacheTakesBounce(push.step.y) && info.x != 0u &&
                frame.cache.x != 0u && cacheKeyFor(info, s.inputs, key);
  MaterialInputs inputs = s.inputs;
#ifdef MG_CACHE_SNAP_UV
  if (insert) inputs = texelInputs(inputs, key.texelUv, key.texelSize);
#endif
  MG_EVALUATE_MATERIAL(inputs, m);
  // Paths of one bounce that missed the same texel all come here (the lookups came first);
  // only the first to insert finds no entry, so the probe range keeps one copy, not many.
  if (insert && cacheFind(key) < 0) {
    float values[MG_CACHE_VALUES];
    cachePack(info.x, m, values);
    cacheWrite(key, values);
  }
  cacheAddCounts();  // the insert's lock counts (no subgroup arithmetic in this pass)
#else
  // A graph the cache does not take (MG_MATERIAL_CACHEABLE is the host's, per graph): no
  // cache code compiled in.
  MG_EVALUATE_MATERIAL(s.inputs, m);
#endif
#else
  MG_EVALUATE_MATERIAL(s.inputs, m);
#endif
#ifdef MG_WAVEFRONT_TILES
  if (tileTexel) {
    tileFillStore(queueSlot, item, texel, m);
    return;
  }
#endif
  storeEvaluated(slot, lightPoint, m);
}

#elif defined(MG_WAVEFRONT_SHADE)
#ifndef MG_MATERIAL_FLOOR
// A live path's material outputs at its hit: a graph whose rest this pass runs gets it from
// its cut's values (the lookup or material pass stored them); any other's, its material
// pass's or the lookup's outputs.
MaterialOutputs materialOutputsOfPath(uint slot, SurfaceHit s) {
#ifdef MG_WAVEFRONT_CUT_FIELD
  if (s.materialId < uint(MG_MATERIAL_COUNT) && mg_materialCutInfo[s.materialId].w != 0u) {
    float values[MG_CACHE_VALUES];
    loadCutValues(slot, mg_materialCutInfo[s.materialId].y, values);
    MaterialOutputs m;
    evaluateMaterialRestInShade(s.materialId, s.inputs, values, m);
    return m;
  }
#endif
  return loadMaterialOutputs(slot, s);
}
#endif

// One vertex of every live path, as the megakernel's loop body shades it: a miss takes the
// environment; a hit its floor material's emission, one light sample (queued as a shadow
// ray) and, unless this is the last bounce, the BSDF's next ray (queued as a live path).
void main() {
  uint i = invocationIndex();
  bool live = i < control.counts.x;
  uint slot = live ? pathQueues[queueIndex(push.step.z, i)] : 0u;
  bool queueShadow = false;
  bool queueNext = false;
  if (live) {
    vec4 throughputField = pathState[fieldIndex(kFieldThroughput, slot)];
    vec4 radianceField = pathState[fieldIndex(kFieldRadiance, slot)];
    vec3 throughput = throughputField.rgb;
    float previousBsdfPdf = throughputField.w;
    vec3 radiance = radianceField.rgb;
    if (radianceField.w < 0.0) {
      radiance += throughput * environmentRadiance(pathState[fieldIndex(kFieldDirection, slot)].xyz);
    } else {
      vec3 origin, direction;
      RayCone cone;
      SurfaceHit s = surfaceOfPath(slot, origin, direction, cone);
      MaterialOutputs m;
#ifdef MG_MATERIAL_FLOOR
      evaluateMaterialDirect(s.materialId, s.inputs, m);
#else
      m = materialOutputsOfPath(slot, s);
#endif
      ShadingPoint p = shadingPointAt(s, m, direction);
      radiance += throughput * m.emission * emissionMisWeight(s, origin, direction, previousBsdfPdf);

      uint bounce = push.step.y;
      bool continues = bounce + 1u < frame.path.y;
      // Key bounce + 1: key 0 is the camera ray's (the generate pass).
      Rng rng = rngForPathVertex(pixelOfSlot(slot), sampleIndexOf(push.step.x), bounce + 1u,
                                 frame.image.w);
      // A look (SceneCulling::look, frame.culling.w) traces only for its counts, as the
      // megakernel's: no light sample, so its paths draw the megakernel's numbers too.
      bool countsOnly = false;
#ifdef MG_HIT_FEEDBACK
      countsOnly = (frame.culling.w & kCullingLook) != 0u;
#endif
      PathState path = loadPathState(slot);  // the vertex's: its ray's state
#ifdef MG_FILTER_GLOSSY_INVERSE
      filterGlossy(p, m, path);  // the path's blur, before light and BSDF sampling use p
#endif
      LightSample light;
      vec3 fCos;
      if (!countsOnly && sampleLightBeforeShadowRay(p, rng, light, fCos)) {
        queueShadow = true;
        float evaluate = 0.0;  // the shadow pass queues the point for its emitter's graph
#if defined(MG_NEE_EVALUATES_EMISSION)
        // An emitter whose emission is its graph's: the point for the material pass after the
        // shadow pass, which multiplies the contribution by the emission there.
        if (light.evaluate) {
          evaluate = 1.0;
          pathState[fieldIndex(kFieldLightHit, slot)] = uintBitsToFloat(uvec4(
              light.hit.instanceIndex, light.hit.primitiveIndex, floatBitsToUint(light.hit.barycentrics)));
          pathState[fieldIndex(kFieldLightOrigin, slot)] = vec4(p.position, light.hit.t);
        }
#elif defined(MG_EMISSIVE_NEE)
        // A free material emits nothing: an emitter whose emission is its graph's adds 0
        // (the megakernel's floor traces that ray and then drops it).
        queueShadow = !light.evaluate;
#endif
#ifdef MG_EMISSIVE_NEE
        light.incident *= lightSampleMisWeight(light, p, continues);
#endif
        pathState[fieldIndex(kFieldShadowOrigin, slot)] =
            vec4(rayOriginTowards(p, light.wi), light.tMax);
        pathState[fieldIndex(kFieldShadowDirection, slot)] =
            vec4(light.wi, uintBitsToFloat(packLightPathState(path)));
        pathState[fieldIndex(kFieldShadowContribution, slot)] =
            vec4(throughput * (fCos * light.incident), evaluate);
      }
      if (continues && continuePath(p, s, rng, throughput, previousBsdfPdf, cone, origin,
                                    direction, path)) {
        queueNext = true;
        storePathState(slot, path);
        pathState[fieldIndex(kFieldOrigin, slot)] = vec4(origin, cone.width);
        pathState[fieldIndex(kFieldDirection, slot)] = vec4(direction, cone.spread);
        pathState[fieldIndex(kFieldThroughput, slot)] = vec4(throughput, previousBsdfPdf);
      }
    }
    pathState[fieldIndex(kFieldRadiance, slot)] = vec4(radiance, 0.0);
  }
  appendToQueue(2u, true, slot, queueShadow);
  appendToQueue(1u - push.step.z, false, slot, queueNext);
}

#elif defined(MG_WAVEFRONT_QUEUE)
// The queues' counts into the indirect arguments of the shadow pass and of the next bounce's
// trace and shade; the appenders start again from 0. Rays are counted here, once a queue.
// One work group, one invocation working.
void main() {
  if (invocationIndex() != 0u) return;
  uint next = control.counts.y;
  uint shadows = control.counts.z;
  control.counts = uvec4(next, 0u, 0u, 0u);
  control.liveGroups = uvec4(workgroupsFor(next), 1u, 1u, 0u);
  control.liveLaunch = uvec4(next, 1u, 1u, 0u);
  control.shadowGroups = uvec4(workgroupsFor(shadows), 1u, 1u, 0u);
  control.shadowLaunch = uvec4(shadows, 1u, 1u, 0u);
  atomicAdd(counters.rays, next + shadows);
#ifdef MG_WAVEFRONT_TILES
  tileQueueHeader.count = 0u;  // this bounce's tiles are published; the next bounce queues anew
#endif
}

#elif defined(MG_WAVEFRONT_SHADOW)
// The queued shadow rays: an unblocked one adds its contribution to its path's radiance. With
// MG_TRANSPARENT_SHADOWS a ray passes maybe-transparent surfaces, evaluating their graphs
// here (transparent_shadow.glsl, the megakernel's), and its contribution is tinted by them.
void main() {
  uint i = invocationIndex();
  if (i >= control.shadowLaunch.x) return;
  uint slot = pathQueues[queueIndex(2u, i)];
  vec4 origin = pathState[fieldIndex(kFieldShadowOrigin, slot)];
#ifdef MG_TRANSPARENT_SHADOWS
  vec4 directionField = pathState[fieldIndex(kFieldShadowDirection, slot)];
  // The segments traced past a surface count as rays, as the megakernel counts them (the
  // queue pass counted the first).
  uint rays = 0u;
  vec3 transmittance = traceShadowTransmittance(
      origin.xyz, directionField.xyz, origin.w,
      shadowPathState(unpackLightPathState(floatBitsToUint(directionField.w))), rays);
  if (rays > 0u) atomicAdd(counters.rays, rays);
  if (all(equal(transmittance, vec3(0.0)))) return;
  vec4 contribution = pathState[fieldIndex(kFieldShadowContribution, slot)];
  contribution.rgb *= transmittance;
#else
  vec3 direction = pathState[fieldIndex(kFieldShadowDirection, slot)].xyz;
  if (traceShadow(origin.xyz, direction, origin.w)) return;
  vec4 contribution = pathState[fieldIndex(kFieldShadowContribution, slot)];
#endif
#ifdef MG_NEE_EVALUATES_EMISSION
  // An emitter's graph to evaluate: into the light points' queue, the bounce's live queue,
  // which the shade pass has read (the binning and material passes that follow evaluate it).
  if (contribution.w != 0.0) {
#ifdef MG_TRANSPARENT_SHADOWS
    pathState[fieldIndex(kFieldShadowContribution, slot)] = contribution;
#endif
    pathQueues[queueIndex(push.step.z, atomicAdd(control.counts.w, 1u))] = slot;
    return;
  }
#endif
  pathState[fieldIndex(kFieldRadiance, slot)].rgb += contribution.rgb;
}

#elif defined(MG_WAVEFRONT_FINISH)
// The round's radiance into the pixel's sum (a path with NaN or infinity dropped, as in the
// megakernel); after the last round the pixel's mean of P paths into the running mean of the
// accumulation buffer.
void main() {
  uint slot = invocationIndex();
  if (slot >= push.chunk.z) return;
  uint round = push.step.x;
  vec3 radiance = pathState[fieldIndex(kFieldRadiance, slot)].rgb;
  vec4 pixelSum = pathState[fieldIndex(kFieldPixelSum, slot)];
  vec3 sum = round == 0u ? vec3(0.0) : pixelSum.rgb;
  if (!any(isnan(radiance)) && !any(isinf(radiance))) sum += radiance;
  uint pathCount = max(frame.path.x, 1u);
  if (round + 1u < pathCount) {
    pathState[fieldIndex(kFieldPixelSum, slot)] = vec4(sum, pixelSum.w);
    return;
  }
  vec3 mean = sum / float(pathCount);
  uint pixel = pixelOfSlot(slot);
#ifdef MG_DEBUG_CACHE_MISSES
  // Thesis Fig. 6.9, as the megakernel's renderPixel: red where a path of this pixel missed
  // the cache in this frame (the lookup pass's flag), this frame's alone (no running mean).
  accumulation[pixel] = vec4(pixelSum.w != 0.0 ? vec3(1.0, 0.0, 0.0) : mean, 1.0);
#else
  uint sampleIndex = frame.environmentSize.z;
  vec3 previous = sampleIndex == 0u ? vec3(0.0) : accumulation[pixel].rgb;
  accumulation[pixel] = vec4(mix(previous, mean, 1.0 / float(sampleIndex + 1u)), 1.0);
#endif
}
#endif
