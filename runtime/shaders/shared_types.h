// GPU structs, binding indices and constants shared by the host (C++) and the path tracer
// (GLSL): one definition, so the two sides cannot drift apart (docs/design/architecture.md).
// Every struct is laid out in vec4-sized fields so std140/std430 and C++ agree.
#ifndef MEMOGRAPH_SHARED_TYPES_H
#define MEMOGRAPH_SHARED_TYPES_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>
namespace memograph::runtime::gpu {
using uint = std::uint32_t;
using uint64 = std::uint64_t;
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define MG_CONSTANT(type, name, value) inline constexpr type name = value
#else
#define MG_CONSTANT(type, name, value) const type name = value
// The 64-bit counter clock of §5.3.3: a real uint64_t where the shader enables the int64
// extensions (MG_CACHE_CLOCK_COUNTER), else two uints with the same 8-byte size and
// alignment, so Counters has one layout either way.
#ifdef MG_CACHE_CLOCK_COUNTER
#define uint64 uint64_t
#else
#define uint64 uvec2
#endif
#endif

// Descriptor set 0 bindings.
MG_CONSTANT(uint, kBindingTlas, 0);
MG_CONSTANT(uint, kBindingFrame, 1);
MG_CONSTANT(uint, kBindingAccumulation, 2);
MG_CONSTANT(uint, kBindingVertices, 3);
MG_CONSTANT(uint, kBindingIndices, 4);
MG_CONSTANT(uint, kBindingInstances, 5);
MG_CONSTANT(uint, kBindingMeshes, 6);
MG_CONSTANT(uint, kBindingLights, 7);
MG_CONSTANT(uint, kBindingEnvironment, 8);
MG_CONSTANT(uint, kBindingTextures, 9);
MG_CONSTANT(uint, kBindingRayCounter, 10);  // gpu::Counters
MG_CONSTANT(uint, kBindingCache, 11);       // the cache's entries (thesis §5.3.1, §5.4.1)
MG_CONSTANT(uint, kBindingTileTexels, 12);  // tile cache: texels in a separate buffer
MG_CONSTANT(uint, kBindingTileLog, 13);     // tile cache: tiles computed this frame (a set)
MG_CONSTANT(uint, kBindingTileImage, 14);   // tile cache: texels in a 2D or 3D storage image
MG_CONSTANT(uint, kBindingTileQueue, 15);   // tile cache, deferred fill: the missing tiles
// LiPaC hit feedback (seeds/001 §3.3.2; MG_HIT_FEEDBACK): one uint per scene instance, its
// hits (or its box's while omitted), then one per hitbox, its box's. Cleared every frame.
MG_CONSTANT(uint, kBindingHitFeedback, 16);
// LiPaC's counting boxes (inactive hitboxes, omitted instances) in a TLAS of their own, so
// that path rays never traverse them and the feedback probe traverses nothing else.
MG_CONSTANT(uint, kBindingCountingBoxes, 17);
// The wavefront path tracer (wavefront.glsl; --shading wavefront): the path state (SoA,
// kPathStateFields vec4 arrays of one slot per pixel), the path queues (two live queues used
// in turn, then the shadow queue, each a slot per pixel) and gpu::WavefrontControl.
MG_CONSTANT(uint, kBindingPathState, 18);
MG_CONSTANT(uint, kBindingPathQueues, 19);
MG_CONSTANT(uint, kBindingWavefrontControl, 20);
MG_CONSTANT(uint, kBindingCount, 21);

// TLAS instance masks and the rays' cull masks. Surfaces answer every path ray; lights'
// quads (Blender area lamps) only BSDF rays, as Cycles' lamps.
MG_CONSTANT(uint, kMaskSurface, 0x7E);
MG_CONSTANT(uint, kMaskLightQuad, 0x01);
MG_CONSTANT(uint, kMaskCountingBox, 0xFF);      // the boxes' own TLAS: every box, every probe
MG_CONSTANT(uint, kRayMaskNoLightQuads, 0x7E);  // camera and shadow rays
MG_CONSTANT(uint, kRayMaskAll, 0x7F);           // BSDF rays

// Animated meshes (Scene::animatedMeshes; seeds/001 §3.3.1: "compute shaders are dispatched
// in each frame to update the vertices for BLAS building"): how a mesh's rest vertices move
// (vertex_motion.h), and what the vertex pass (vertex_motion.comp) reads. One dispatch moves
// every mesh the frame needs, a work group row per mesh, before one barrier and the batched
// BLAS updates and rebuilds.
struct VertexMotion {
  vec4 drift;  // xyz: a constant velocity in object space, units a second
  vec4 wave;   // x: a cloth's length along +x from its pole (0: no wave), y: the wave's phase
};
// A mesh the pass moves this frame.
struct VertexMotionJob {
  VertexMotion motion;
  // x: its first vertex in the scene's vertex buffer, y: its vertex count, z: its first rest
  // vertex, w: the sign (as float bits) that turns its triangles' normals to its own side.
  uvec4 range;
};
// A rest vertex: position, the mesh's own normal (kept where the moved triangles around it
// are degenerate), and (x first, y count) its triangles among the corner triples.
struct VertexMotionRest {
  vec4 position;
  vec4 normal;
  uvec4 triangles;
};
// Its push constants: buffer device addresses as (low, high) uint pairs.
struct VertexMotionPush {
  uvec4 sources;  // xy: the jobs, zw: the rest vertices
  uvec4 targets;  // xy: the corner triples (uvec4: rest-vertex indices of a triangle), zw: the
                  // scene's vertices (gpu::Vertex), written in place
  vec4 time;      // x: seconds
};
MG_CONSTANT(uint, kVertexMotionWorkgroup, 64);

// Compute work-group edge of the ray-query backend.
MG_CONSTANT(uint, kWorkgroupSize, 8);
// The deferred tile fill's launch: rows of kFillRowInvocations (one per texel of a queue
// slot), compute work groups of kFillWorkgroupSize along a row.
MG_CONSTANT(uint, kFillRowInvocations, 4096);
MG_CONSTANT(uint, kFillWorkgroupSize, 64);

// The wavefront path tracer's passes (MG_WAVEFRONT_PASS, wavefront.glsl), in the order one
// bounce records them: generate once a round, then trace, (with material graphs: with the
// texel cache a lookup, then bin count, bin offsets, bin scatter, with traced inputs the
// traced-inputs pass, one material pass per graph,) shade, queue and shadow per bounce,
// finish once a round.
MG_CONSTANT(uint, kWavefrontGenerate, 0);
MG_CONSTANT(uint, kWavefrontTrace, 1);
MG_CONSTANT(uint, kWavefrontShade, 2);
MG_CONSTANT(uint, kWavefrontQueue, 3);
MG_CONSTANT(uint, kWavefrontShadow, 4);
MG_CONSTANT(uint, kWavefrontFinish, 5);
MG_CONSTANT(uint, kWavefrontBinCount, 6);
MG_CONSTANT(uint, kWavefrontBinOffsets, 7);
MG_CONSTANT(uint, kWavefrontBinScatter, 8);
MG_CONSTANT(uint, kWavefrontMaterial, 9);
MG_CONSTANT(uint, kWavefrontLookup, 10);
MG_CONSTANT(uint, kWavefrontTracedInputs, 11);
MG_CONSTANT(uint, kWavefrontPassCount, 12);
// Compute work-group size of the wavefront passes (one invocation per queued path).
MG_CONSTANT(uint, kWavefrontWorkgroupSize, 64);
// The material passes' work-group size: a graph keyed by its cut gathers the misses of a
// work group and evaluates them together (wavefront.glsl materialPassThroughCut), which pays
// where a group spans many subgroups: at a few percent of misses most 32-lane subgroups hold
// one, and a group of 64 has only two.
MG_CONSTANT(uint, kWavefrontMaterialWorkgroupSize, 256);
// vec4 fields of a path's state: origin and cone width, direction and cone spread,
// throughput and the last BSDF pdf, radiance and the hit's t, the hit (instance, primitive,
// barycentrics as bits), the shadow ray's origin and length, its direction, the contribution
// it brings when unblocked, and the pixel's sum over the rounds.
MG_CONSTANT(uint, kPathStateFields, 9);
// With material graphs, four more: the material's outputs at the hit (what the shade pass's
// BSDF needs), written by the material passes.
MG_CONSTANT(uint, kPathStateFieldsWithMaterials, 13);
// With graphs that read the path state (Light Path, MG_OMIT_PATH_INPUTS undefined), one more:
// the ray's kind and its depths (path_shading.glsl PathState) from one bounce to the next.
MG_CONSTANT(uint, kPathStateFieldsForPathInputs, 1);
// With emitters whose light samples evaluate their graphs, two more after those: the sample's
// point (its hit, and the shading point it is seen from), for the material pass after the
// shadow pass.
MG_CONSTANT(uint, kPathStateFieldsForLightPoints, 2);
// With materials of BSDF lobes (MG_BSDF_LOBES), two per lobe after those: its weight and kind,
// its parameters (MaterialOutputs::lobeWeight, lobeParameters; MG_MAX_LOBES of them).
MG_CONSTANT(uint, kPathStateFieldsForLobes, 8);
// With materials that read a traced input (Ambient Occlusion, Bevel; MG_OMIT_TRACED_INPUTS
// undefined), one more after those: the traced-inputs pass's Bevel normal and AO fraction at
// the hit, for its material pass.
MG_CONSTANT(uint, kPathStateFieldsForTracedInputs, 1);
// With Filter Glossy (MG_FILTER_GLOSSY_INVERSE), one more after all those (and after
// --shared-primary's two): the path's smallest bounce pdf (path_shading.glsl PathState).
MG_CONSTANT(uint, kPathStateFieldsForMinRayPdf, 1);

// The wavefront's queue counts and indirect arguments (binding kBindingWavefrontControl).
// Each launch block is a VkDispatchIndirectCommand (work groups) or a
// VkTraceRaysIndirectCommandKHR (invocations) in its xyz. With material graphs the block
// goes on with three uvec4 per material bin (one bin per distinct graph): the bin's material
// pass's VkDispatchIndirectCommand, then (hits counted, first place in the material-sorted
// queue, scatter cursor, hits in the batch), then the same for the bin's queued tiles (with
// the tile cache; zero otherwise).
struct WavefrontControl {
  uvec4 counts;        // x: paths in the live queue, y: appended to the next, z: shadow rays,
                       // w: light points queued by the shadow pass (emitters' graphs)
  uvec4 liveGroups;    // compute passes over the live queue
  uvec4 liveLaunch;    // the pipeline backend's trace of the live queue
  uvec4 shadowGroups;  // the query backend's shadow pass
  uvec4 shadowLaunch;  // the pipeline backend's shadow pass
  // With traced inputs: the hits whose material reads one, the material-sorted queue's first
  // places (the bin offsets pass puts those bins first), for the traced-inputs pass.
  uvec4 tracedGroups;  // the query backend's traced-inputs pass
  uvec4 tracedLaunch;  // the pipeline backend's
};
// Push constants of every wavefront pass. A round of one path a pixel runs in chunks of at
// most `slots` pixels when the image has more pixels than the path state has slots (its
// capacity, RendererOptions::wavefrontPaths): chunk c covers pixels c * slots onwards.
struct WavefrontPush {
  uvec4 step;   // x round (path index of every pixel), y bounce, z live queue (0 or 1), w bin
  uvec4 chunk;  // x slots (the path state's capacity), y the chunk's first pixel, z its pixels,
                // w kWavefront* bits below
};
// A material pass shared by graphs of one shape (material instances) takes its bin's graph in
// push constants after WavefrontPush: a uvec4 (x its first texture slot), then its parameter
// block, kMaterialParameterPushOffset bytes from the start. The push range holds at most
// (the device's maxPushConstantsSize - that offset) / 4 floats; a group with more parameters
// gets a pass per graph instead.
MG_CONSTANT(uint, kMaterialParameterPushOffset, 48);
// WavefrontPush::chunk.w bits: the trace pass counts LiPaC's hit feedback (a counting frame);
// the binning and material passes bin and evaluate light samples' points, not hits.
MG_CONSTANT(uint, kWavefrontCountsHits, 1);
MG_CONSTANT(uint, kWavefrontLightPoints, 2);

// FrameConstants::flags bits.
MG_CONSTANT(uint, kFlagSharedPrimaryRay, 1);
MG_CONSTANT(uint, kFlagEnvironmentImage, 2);
// FrameConstants::culling.w bits (LiPaC).
MG_CONSTANT(uint, kCullingLook, 1);  // a look: it only counts (no shadow rays)

// Texel cache (thesis §4.2-4.5, §5.3). An entry is kCacheEntryHeader uints (the 32-bit
// key hash H1 of eq. 5.9, then the eviction metadata) followed by the material's written
// outputs, as fp32 bits or (MG_CACHE_VALUE_FP16) two halves per uint (§5.3.1); the host
// picks the value count from the largest cacheable material.
MG_CONSTANT(uint, kCacheEntryHeader, 2);
// With the update counter (§5.3.4, last paragraph; MG_CACHE_UPDATE_COUNTER) the header has
// a third uint, bumped by every write, so a reader detects a write even when the key was
// restored (the A-B-A race of the key-only check).
MG_CONSTANT(uint, kCacheEntryHeaderWithCounter, 3);
// The tile cache's subgroup fill (§5.4.3; not the deferred fill) adds one uint after the
// header above: the count of the locked tile's texels stored so far. Each lane that stores
// a texel fences and adds 1 to it; the add that brings it to W*H publishes the tile
// (tile_cache.glsl tileCountTexels). It is 0 whenever the entry is unlocked, and nothing
// else reads or writes it (the clock and the update counter have other writers). 4 bytes
// an entry: 4 MiB at the default 2^20 tiles.
MG_CONSTANT(uint, kCacheEntryTileCountWords, 1);
MG_CONSTANT(uint, kCacheKeyEmpty, 0u);          // a cleared entry; H1 is never 0
MG_CONSTANT(uint, kCacheKeyLock, 0xFFFFFFFFu);  // CACHE_LOCK of §5.3.4; H1 is never this
MG_CONSTANT(uint, kCacheMaxProbe, 16);          // linear probing distance D: 1..16
// Eviction policies (MG_CACHE_EVICTION): §4.5 / §5.3.3.
MG_CONSTANT(uint, kCacheEvictionNone, 0);    // insert only into an empty entry
MG_CONSTANT(uint, kCacheEvictionLru, 1);     // least recently used, frame clock in the metadata
MG_CONSTANT(uint, kCacheEvictionLrw, 2);     // least recently written, frame clock
MG_CONSTANT(uint, kCacheEvictionRandom, 3);  // a pseudo-random entry of the probe range
// How the texel cache reads a key space (MG_CACHE_FILTER; docs/design/memoization.md,
// "Filtering"): the nearest texel or voxel of the nearest level (eq. 5.5-5.7); trilinear, the
// 2x2 texels (2x2x2 voxels) around the hit at the two levels around its continuous level,
// blended (thesis §7's trilinear interpolation between mip levels); stochastic, one of those
// entries picked with its blend weight as probability (seed 002 §3.2's random selection by
// weight), whose mean over samples is the trilinear value.
MG_CONSTANT(uint, kCacheFilterNearest, 0);
MG_CONSTANT(uint, kCacheFilterTrilinear, 1);
MG_CONSTANT(uint, kCacheFilterStochastic, 2);
// Bits of a material's output mask (which MaterialOutputs members an entry stores, in this
// order: baseColor 3 floats, metallic 1, roughness 1, normal 3, emission 3, opacity 1,
// specular 1, specularTint 1, cyclesPrincipled 1; the later members came last, so the older
// members kept their places).
MG_CONSTANT(uint, kCacheOutputBaseColor, 1);
MG_CONSTANT(uint, kCacheOutputMetallic, 2);
MG_CONSTANT(uint, kCacheOutputRoughness, 4);
MG_CONSTANT(uint, kCacheOutputNormal, 8);
MG_CONSTANT(uint, kCacheOutputEmission, 16);
MG_CONSTANT(uint, kCacheOutputOpacity, 32);
MG_CONSTANT(uint, kCacheOutputSpecular, 64);
MG_CONSTANT(uint, kCacheOutputSpecularTint, 128);
MG_CONSTANT(uint, kCacheOutputCyclesPrincipled, 256);
// The BSDF lobes (MaterialOutputs::lobeCount, lobeWeight, lobeParameters; nodes/bsdf.inc):
// the count, then per lobe of MG_MAX_LOBES its weight, kind, roughness and IOR.
MG_CONSTANT(uint, kCacheOutputLobes, 512);
MG_CONSTANT(uint, kCacheLobeValues, 25);  // 1 + MG_MAX_LOBES (4) x 6
// The lobes' own normals (MaterialOutputs::lobeParameters z, w of each of MG_MAX_LOBES), only
// for a material that gives some lobe one (the compiler's `lobeNormals` output), after the
// lobes: the others' entries keep their size.
MG_CONSTANT(uint, kCacheOutputLobeNormals, 1024);
MG_CONSTANT(uint, kCacheLobeNormalValues, 8);  // MG_MAX_LOBES (4) x 2
// The key domain of a material's cut (compiler/cut.h) as the texel cache keys it
// (mg_materialCutInfo.x, MG_CACHE_CUTS): none runs the whole graph uncached; uv keys the
// cut's values by (material, uv texel, mip level) as §5.3.2 keys whole outputs; object by
// (material, instance or mesh, object-space voxel, level); world by (material, world-space
// voxel, level).
MG_CONSTANT(uint, kCacheCutNone, 0);
MG_CONSTANT(uint, kCacheCutUv, 1);
MG_CONSTANT(uint, kCacheCutObject, 2);
MG_CONSTANT(uint, kCacheCutWorld, 3);

// Tile cache (thesis §4.6, §5.4): where a tile's texels live (MG_TILE_STORAGE, §5.4.1).
MG_CONSTANT(uint, kTileStorageEntry, 0);      // after the key and metadata, in the entry
MG_CONSTANT(uint, kTileStorageBuffer, 1);     // a separate buffer, entry-major
MG_CONSTANT(uint, kTileStorageTexture2D, 2);  // a 2D image; value groups side by side in x
MG_CONSTANT(uint, kTileStorageTexture3D, 3);  // a 3D image; value groups stacked in z
// The per-frame set of computed tiles that counts duplicates (§6.7.2): a power of two.
MG_CONSTANT(uint, kTileLogEntries, 1u << 20);
MG_CONSTANT(uint, kTileLogProbe, 8);

// The deferred tile fill's queue (binding kBindingTileQueue): a header, then one item per
// missing tile, written whole by the request that locked its entry; the fill pass runs one
// invocation per texel and the last of a tile's invocations publishes it.
struct TileQueueHeader {
  uint count;  // items requested this frame; those past the capacity were not stored
  uint pad0;
  uint pad1;
  uint pad2;
};
struct TileFillItem {
  uint entry;    // the locked entry
  uint keyBase;  // CacheKey::base and ::hash, to publish the entry under
  uint keyHash;
  uint materialId;
  uint level;  // the tile's mip level (int bits)
  uint tileX;  // the tile's position in multiples of the tile size (float bits)
  uint tileY;
  uint texelsDone;  // texels stored so far (atomic); the one that makes it W*H publishes
};
// Light::positionOrDirection.w
MG_CONSTANT(uint, kLightPoint, 0);
MG_CONSTANT(uint, kLightDirectional, 1);
MG_CONSTANT(uint, kLightSpot, 2);
// An emissive triangle (NEE, sampled by power): intensity.x the CDF up to and including it
// over the emissive triangles, intensity.y/z the index of the first emissive triangle in the
// light buffer and their count (as floats), spot.x/y instance and primitive (uint bits),
// spot.z its world-space area. Emissive triangles follow the punctual lights.
MG_CONSTANT(uint, kLightTriangle, 3);

// Mesh::flags bits.
MG_CONSTANT(uint, kMeshHasUvs, 1);
MG_CONSTANT(uint, kMeshHasTangents, 2);
MG_CONSTANT(uint, kMeshHasColors, 4);

// Per-frame constants (uniform buffer).
struct FrameConstants {
  vec4 cameraPosition;    // xyz; w: pixel spread angle (thesis §2.2, primary cone)
  vec4 cameraRight;       // xyz scaled by tan(fov/2) * aspect
  vec4 cameraUp;          // xyz scaled by tan(fov/2)
  vec4 cameraForward;     // xyz unit; w: time in seconds
  vec4 environment;       // rgb constant radiance (or scale of the image); w unused
  uvec4 image;            // x width, y height, z frame index, w seed
  uvec4 path;             // x paths per pixel P, y rays per path L, z flags, w light count
  uvec4 environmentSize;  // x width, y height of the equirectangular image; z sample index
                          // in the accumulation (0 restarts it); w unused
  // Cache: x entries S (0: no cache), y frame clock (frame + 1), z mip bias of eq. 5.5
  // (float bits), w tiles per row of the tile cache's storage image.
  uvec4 cache;
  // LiPaC (MG_HIT_FEEDBACK): x: 1 in x 8×8-pixel blocks counts its rays this frame, each
  // count weighted x (CullingOptions::feedbackStride); y: which blocks and paths, the
  // counting frame's index (the frame over CullingOptions::feedbackEvery); z: z of each
  // pixel's P paths count, each count weighted P / z besides (CullingOptions::feedbackPaths;
  // 0: every path); w kCulling* bits: kCullingLook, a look, whose image the frame replaces,
  // so it only counts (its paths trace no shadow rays).
  uvec4 culling;
};

// The megakernel's push constants: which of a pixel's P paths this trace dispatch traces
// (runtime/trace/megakernel/path_dispatches.h). A frame's paths may be traced by several
// dispatches, each adding its paths' share of the pixel's mean.
struct TraceDispatchPush {
  // x the first path, y how many (cyclically from x, modulo P), z 1 where an earlier
  // dispatch of the frame folded its share into the running mean already (this one adds to
  // it), w unused.
  uvec4 paths;
};

// Counters the shader adds to (binding kBindingRayCounter), in vec4-sized groups. The first
// kCountersPerFrameUints are cleared before every frame; the rest only with the cache,
// before the first frame.
struct Counters {
  uint rays;          // closest-hit and shadow rays traced
  uint cacheLookups;  // cache lookups of cacheable materials
  uint cacheHits;
  uint cacheMisses;
  // Tile cache (§5.4.3): tiles computed by a subgroup, of which already computed this frame
  // by another subgroup (§6.7.2), and misses that evaluated their own hit because fewer
  // lanes than texels were active, or because a callable repacked the subgroup. With the
  // deferred fill: tiles queued, 0, requests that found the queue full, 0.
  uint cacheTilesComputed;
  uint cacheDuplicateTiles;
  uint cacheTileFallbacks;
  uint cacheTileRepacks;
  // Both caches' inserts (cacheLockEvicting): locks that chose their entry beside a locked one
  // in the probe range (with the tile cache, often a tile still being computed: a lookup of
  // that tile misses it and, under lru and lrw, locks a second entry for the same tile), and
  // locks whose chosen entry another invocation had locked first (given up).
  uint cacheLocksBesideALock;
  uint cacheLocksContended;
  // Persistent across frames.
  uint cacheOccupancy;  // entries ever filled (an empty entry's first write); never falls
  // Tile cache: tiles published (the key written after the tile's last texel) since the
  // cache was cleared, by the subgroup fill's or the deferred fill's last texel.
  uint cacheTilesPublished;
  uint64 cacheClock;  // the 64-bit atomic counter clock of §5.3.3 (MG_CACHE_CLOCK_COUNTER)
  uint pad0;          // to a multiple of 16 bytes
  uint pad1;
};
MG_CONSTANT(uint, kCountersPerFrameUints, 10);

// One vertex of the global vertex buffer; positions first so the BLAS reads them in place.
struct Vertex {
  vec4 position;  // xyz; w: u
  vec4 normal;    // xyz; w: v
  vec4 tangent;   // xyz; w: handedness
  vec4 color;
};

// One mesh's range in the global vertex and index buffers.
struct Mesh {
  uvec4 ranges;  // x first vertex, y first index, z flags, w triangle count
  // Blender's automatic texture space of the mesh (Generated coordinates): xyz the centre
  // of its object-space bounding box and half its extent (a zero extent becomes 1);
  // Generated = (objectPosition - location) / (2 size) + 0.5. w unused.
  vec4 textureSpaceLocation;
  vec4 textureSpaceSize;
};

// One placed instance; the TLAS's custom index points here.
struct Instance {
  mat4 objectToWorld;
  mat4 normalToWorld;  // inverse transpose of objectToWorld
  mat4 worldToObject;  // inverse of objectToWorld (Object coordinates)
  // x mesh, y material, z the mesh whose triangles the TLAS holds for it: x, or in a culled
  // render one of x's LODs (seeds/001 §3.3.1; Scene::meshLods), whose primitive indices a hit
  // reports; w unused.
  uvec4 ids;
  vec4 objectInfo;  // x: random in [0, 1) (a hash of the instance index); y: emissive
                    // NEE's area pdf of any point of this instance (0: not a light); zw unused
};

struct Light {
  vec4 positionOrDirection;  // xyz; w: kLightPoint or kLightDirectional (as float)
  vec4 intensity;            // rgb: W/sr (point, spot) or irradiance (directional)
  vec4 spot;                 // spot: xyz cone axis (unit), w cos of the half angle
  vec4 spotSmooth;           // spot: x smoothing width in cosine ((1 - cos) * blend)
};

#ifdef __cplusplus
static_assert(sizeof(TileQueueHeader) == 16 && sizeof(TileFillItem) == 32);
static_assert(sizeof(VertexMotionJob) == 48 && sizeof(VertexMotionRest) == 48);
static_assert(sizeof(WavefrontControl) == 112 && sizeof(WavefrontPush) == 32);
// The material instance's ivec4 sits between the WavefrontPush and the parameters.
static_assert(kMaterialParameterPushOffset == sizeof(WavefrontPush) + 16);
static_assert(sizeof(Counters) % 16 == 0 &&
              offsetof(Counters, cacheOccupancy) == kCountersPerFrameUints * sizeof(uint));
}  // namespace memograph::runtime::gpu
#else
#undef uint64
#endif
#undef MG_CONSTANT
#endif
