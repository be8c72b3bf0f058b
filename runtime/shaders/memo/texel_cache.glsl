// The texel cache of thesis §4.2-4.5 and §5.3: material graph outputs memoized in one hash
// table of entries keyed by (material, mip level, texel). Included by path_tracer.glsl (and
// by wavefront.glsl's lookup and material passes, MG_WAVEFRONT) when the host defines
// MG_CACHE_TEXEL, with
//   MG_CACHE_VALUES    floats per entry (the largest cacheable material's written outputs),
//   MG_CACHE_PROBE     the linear probing distance D (1..kCacheMaxProbe),
//   MG_CACHE_EVICTION  kCacheEviction{None, Lru, Lrw, Random} (0..3),
//   MG_CACHE_UPDATE_COUNTER  (optional) the update-counter read check of §5.3.4,
//   MG_CACHE_VALUE_FP16      (optional) values as two halves per uint (§5.3.1),
//   MG_CACHE_CLOCK_COUNTER   (optional) the 64-bit atomic counter clock of §5.3.3 instead of
//                            the frame clock, with MG_CACHE_CLOCK_SHIFT (bits kept),
//   MG_CACHE_SNAP_UV         (optional) a miss evaluates the graph at its texel centre (§6.1),
//   MG_CACHE_REFRESH_UV, MG_CACHE_REFRESH_VOXEL (optional) frames a uv key (a texel), a
//                            voxel key (object or world space) lives before its cell is keyed
//                            (and filled) anew at another point of the cell (cacheKeyOfHashes),
//   MG_CACHE_STAMP_BY_SUBGROUP (optional; needs subgroup arithmetic and every invocation of
//                            the subgroup calling cacheStampReads) lru's counter-clock stamps
//                            of reads, one clock atomic per subgroup (cacheStampReads),
//   MG_CACHE_QUIESCENT_READS (optional) no invocation of the including dispatch writes a
//                            value: reads skip §5.3.4's check (MG_CACHE_COHERENT).
//   MG_CACHE_FILTER          (optional) kCacheFilter{Trilinear,
//                            Stochastic}: how a lookup reads the key space (cacheFilterEntry);
//                            unset, the nearest entry of the nearest level.
//   MG_CACHE_CUTS            (optional; the megakernel's switch dispatch and the wavefront)
//                            materials that are not cacheable as a whole are keyed by their
//                            cut (compiler/cut.h): uv texels, object-space or world-space
//                            voxels (cacheCutKeyFor); materials.glsl then provides
//                            mg_materialCutInfo, and in the megakernel the cut and rest
//                            switches (evaluateMaterialThroughCut).
//   MG_CACHE_CUT_PASS        (optional; a wavefront material pass of a graph keyed by its
//                            cut) every read or fill goes through the cut, so the whole
//                            graph's fill (evaluateMaterialDirect, cachePack) is not compiled
//                            in: the pass holds one copy of its graph.
// The entry count S, the frame clock and the mip bias come per frame in frame.cache. The
// includer declares `counters` (gpu::Counters at kBindingRayCounter): the occupancy and the
// counter clock live there.
// materials.glsl provides mg_materialCacheInfo[id]: x the output mask (0: not cacheable),
// y ID0, z ID1 (two independent hashes of the material's graph, eq. 5.8-5.9).
#ifndef MG_TEXEL_CACHE_GLSL
#define MG_TEXEL_CACHE_GLSL
#extension GL_EXT_control_flow_attributes : require
// The entry protocol (§5.3.4) is written for the Vulkan memory model: every word that one
// invocation writes while another may read it (keys, update counters, clocks, tile counts
// and the values in buffers) is accessed only by atomics of device scope, and the fences
// between them are acquire-release fences of device scope (cacheFence). Under this model a
// plain load that races with a store is a data race (undefined), and a fence synchronizes
// only through an atomic on each side: the plain coherent loads and memoryBarrier() that
// the protocol used before ordered the accesses on x86 and NVIDIA in practice, not by the
// model's rules. The renderer enables vulkanMemoryModel and vulkanMemoryModelDeviceScope.
#extension GL_KHR_memory_scope_semantics : require
#pragma use_vulkan_memory_model

// The entries' words (kCacheEntryHeader[WithCounter] + values each, gpu::cacheEntryWords):
// the S keys first, one word an entry (cacheKeyWord), then each entry's record
// (cacheEntryOffset): its clock, its update counter, the subgroup tile fill's count, then its
// values from kCacheHeader. The keys lie apart so that the D keys a lookup compares
// (cacheFind) are D adjacent words, one or two 32-byte sectors, where with each key at the
// head of its record they were D records apart: at D = 8 and 10-word entries, 8 sectors a
// lookup before the entry's own. (On the H200 it left the wavefront's lookup pass as it was,
// 15.1 against 15.3 ms with the frame clock: the pass is not bound by the bytes it reads.)
const uint kCacheClockWord = 0u;
const uint kCacheCounterWord = 1u;  // with MG_CACHE_UPDATE_COUNTER
#ifdef MG_CACHE_UPDATE_COUNTER
const uint kCacheMetaWords = kCacheEntryHeaderWithCounter - 1u;  // clock, update counter
#else
const uint kCacheMetaWords = kCacheEntryHeader - 1u;  // clock
#endif
#if defined(MG_CACHE_TILE) && !defined(MG_TILE_FILL_DEFERRED)
// The subgroup tile fill's count of stored texels (tile_cache.glsl tileCountTexels), after
// the metadata: the record is clock[, update counter], count.
const uint kCacheTileCount = kCacheMetaWords;
const uint kCacheHeader = kCacheMetaWords + kCacheEntryTileCountWords;
#else
const uint kCacheHeader = kCacheMetaWords;
#endif
// Words per entry's values: one per fp32 value, or one per two halves (§5.3.1: 16-bit floats
// "usually provide sufficient precision" for colours and normals). The tile cache stores
// its texels through the same cacheStoreValues / cacheLoadValues.
#ifdef MG_CACHE_VALUE_FP16
const uint kCacheValueWords = (uint(MG_CACHE_VALUES) + 1u) / 2u;
#else
const uint kCacheValueWords = uint(MG_CACHE_VALUES);
#endif
// A record's words: the header, then one texel's values (texel cache), a tile's texels (tile
// cache, stored in the entry) or none (tiles stored elsewhere); the tile cache's host
// defines the last.
#ifdef MG_CACHE_ENTRY_WORDS
const uint kCacheRecordWords = kCacheHeader + uint(MG_CACHE_ENTRY_WORDS);
#else
const uint kCacheRecordWords = kCacheHeader + kCacheValueWords;
#endif

// MG_CACHE_QUIESCENT_READS: a dispatch in which no invocation writes a value: the wavefront's
// lookup pass, which a pipeline barrier separates from the passes that fill entries (the
// material passes). Its invocations store only clock words (a read's stamp) and, with the
// tile cache, lock a missing tile's entry and may restore it (tileEnqueue), both with
// atomics; the values a read finds under a key stay that key's until the fill pass. So a
// read needs neither §5.3.4's check (its fences and second key load: two more round trips
// in the chain of dependent loads from the queue to the values) nor coherent loads, which a
// GPU may keep out of its L1: the lanes of a subgroup that hit one texel (neighbouring
// pixels) can then share its lines there. On the H200 the pass went from 14.7 to 5.8 ms
// (classroom, 1080p, P = 6, L = 4, frame clock; tile cache 20.6 to 8.9 ms). A key seen
// stale there (locked meanwhile) still names the values beside it; a stale key or clock only
// steers tileEnqueue's choice of a slot, whose lock is an atomic exchange that sees the true
// key. What the fill passes wrote, the barrier made visible. Two stamps of one word race as
// before: each stores a valid clock.
#ifdef MG_CACHE_QUIESCENT_READS
#define MG_CACHE_COHERENT
#else
#define MG_CACHE_COHERENT coherent
#endif

// Entries as one flat uint array so the key can be swapped atomically (§5.3.4). Coherent:
// other invocations of the same dispatch read what this one writes.
layout(set = 0, binding = kBindingCache, std430) MG_CACHE_COHERENT buffer CacheBlock {
  uint cacheData[];
};

// The storage a cache fence orders: the cache buffer, and image memory too where values live
// in a storage image (--tile-storage texture2d|texture3d, the self-test's image modes).
#ifdef MG_CACHE_VALUES_IN_IMAGE
#define MG_CACHE_FENCE_STORAGE (gl_StorageSemanticsBuffer | gl_StorageSemanticsImage)
#else
#define MG_CACHE_FENCE_STORAGE gl_StorageSemanticsBuffer
#endif

// A word of the table that other invocations may write meanwhile: a relaxed atomic load or
// store of device scope. Its order against the other words comes from cacheFence; being
// atomic is what lets the fences synchronize through it (fence synchronization of the Vulkan
// memory model) and what keeps the race of a seqlock read with a writer defined.
uint cacheLoadWord(uint word) {
  return atomicLoad(cacheData[word], gl_ScopeDevice, gl_StorageSemanticsBuffer,
                    gl_SemanticsRelaxed);
}
void cacheStoreWord(uint word, uint value) {
  atomicStore(cacheData[word], value, gl_ScopeDevice, gl_StorageSemanticsBuffer,
              gl_SemanticsRelaxed);
}

// The read-modify-writes of the protocol (locks, unlocks, counters): relaxed as well, of device
// scope; cacheFence orders them.
uint cacheExchangeWord(uint word, uint value) {
  return atomicExchange(cacheData[word], value, gl_ScopeDevice, gl_StorageSemanticsBuffer,
                        gl_SemanticsRelaxed);
}
uint cacheCompareExchangeWord(uint word, uint expected, uint value) {
  return atomicCompSwap(cacheData[word], expected, value, gl_ScopeDevice,
                        gl_StorageSemanticsBuffer, gl_SemanticsRelaxed,
                        gl_StorageSemanticsBuffer, gl_SemanticsRelaxed);
}
uint cacheAddWord(uint word, uint value) {
  return atomicAdd(cacheData[word], value, gl_ScopeDevice, gl_StorageSemanticsBuffer,
                   gl_SemanticsRelaxed);
}

// MG_CACHE_QUIESCENT_READS: no invocation of the dispatch writes a value, and none writes a
// key either unless it is the tile cache's lookup pass (tileEnqueue locks entries). A word
// nothing writes meanwhile races with nothing, so a plain load is defined, and a GPU may
// serve it from its L1, which it does not for an atomic. Everywhere else relaxed atomics.
#ifdef MG_CACHE_QUIESCENT_READS
uint cacheLoadValueWord(uint word) { return cacheData[word]; }
#else
uint cacheLoadValueWord(uint word) { return cacheLoadWord(word); }
#endif
#if defined(MG_CACHE_QUIESCENT_READS) && !defined(MG_CACHE_TILE)
uint cacheLoadKeyWord(uint word) { return cacheData[word]; }
#else
uint cacheLoadKeyWord(uint word) { return cacheLoadWord(word); }
#endif

// Counts of this invocation, added to gpu::Counters once per pixel.
uint g_cacheLookups = 0u;
uint g_cacheHits = 0u;
uint g_cacheMisses = 0u;
// Whether any lookup of this invocation missed: the debug view of thesis Fig. 6.9.
bool g_cacheMissed = false;
// This invocation's locks beside a locked entry, and locks lost to another invocation's.
uint g_locksBesideALock = 0u;
uint g_locksContended = 0u;

// Adds this invocation's lookups, hits and misses to gpu::Counters: with subgroup arithmetic
// one atomic each per subgroup, so every invocation of the subgroup must call it.
void cacheAddCounts() {
#ifdef MG_SUBGROUP_RAY_COUNT
  uvec3 cacheCounts = subgroupAdd(uvec3(g_cacheLookups, g_cacheHits, g_cacheMisses));
  if (subgroupElect() && cacheCounts.x > 0u) {
#else
  uvec3 cacheCounts = uvec3(g_cacheLookups, g_cacheHits, g_cacheMisses);
  if (cacheCounts.x > 0u) {
#endif
    atomicAdd(counters.cacheLookups, cacheCounts.x);
    atomicAdd(counters.cacheHits, cacheCounts.y);
    atomicAdd(counters.cacheMisses, cacheCounts.z);
  }
#ifdef MG_SUBGROUP_RAY_COUNT
  uvec2 lockCounts = subgroupAdd(uvec2(g_locksBesideALock, g_locksContended));
  if (subgroupElect() && any(notEqual(lockCounts, uvec2(0u)))) {
#else
  uvec2 lockCounts = uvec2(g_locksBesideALock, g_locksContended);
  if (any(notEqual(lockCounts, uvec2(0u)))) {
#endif
    atomicAdd(counters.cacheLocksBesideALock, lockCounts.x);
    atomicAdd(counters.cacheLocksContended, lockCounts.y);
  }
}

// Scene material `materialId`'s cache record (mg_materialCacheInfo; none past the scene's).
uvec4 cacheInfoOf(uint materialId) {
  return materialId < uint(mg_materialCacheInfo.length()) ? mg_materialCacheInfo[materialId]
                                                          : uvec4(0u);
}

// The 32-bit PCG hash (O'Neill 2014, in the RXS-M-XS form of Jarzynski and Olano 2020),
// the hash() of eq. 5.8-5.9; runtime::pcgHash is the host's copy. Defined here, not taken
// from the node library's prelude, so every node library works with the cache.
uint cachePcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

struct CacheKey {
  uint base;     // first entry of the probe range: I of eq. 5.10
  uint hash;     // H1 of eq. 5.9, stored in the entry; never kCacheKeyEmpty or kCacheKeyLock
  vec2 texelUv;  // the texel's centre (û, v̂ of eq. 5.6-5.7 over 2^m; with
                 // MG_CACHE_REFRESH_UV this epoch's point of the texel): where a snapped miss
                 // evaluates the graph (§6.1)
  float texelSize;  // 2^-m: a texel's width in uv, the snapped evaluation's footprint
};

// Eq. 5.2-5.5: the mip level m of the cache's virtual texture at this hit. False when the
// hit has no usable texture coordinates (non-finite), which then bypasses the cache.
bool cacheMipLevel(MaterialInputs inputs, out int m) {
  vec2 uv = inputs.uv.v;
  // Eq. 5.2-5.4: the shorter footprint axis in texture space (the higher texel density).
  float lMin = min(length(inputs.uv.x), length(inputs.uv.y));
  // Eq. 5.5 prints m = round(log2(l_min) + bias) while eq. 5.1 defines m as log2 of the
  // texel *density*; a texel one footprint wide has density 1 / l_min, so the level is
  // round(-log2(l_min) + bias) (a larger footprint -> coarser texels; positive bias ->
  // finer). Without derivatives (lMin 0) the finest level we allow is used.
  float bias = uintBitsToFloat(frame.cache.z);
  float level = lMin > 0.0 ? -log2(lMin) + bias : 24.0;
  m = 0;
  if (isnan(level) || any(isnan(uv)) || any(isinf(uv))) return false;
  m = int(clamp(round(level), -24.0, 24.0));
  return true;
}

// The key of hashes H0 and H1 (eq. 5.8-5.9): H1 is stored, kept off the empty and locked
// values; eq. 5.10: the first probed entry is I = H0 mod (S - D) (the host guarantees S > D).
// texelUv and texelSize are the caller's. `refreshFrames` (a constant: kCacheRefreshUv or
// kCacheRefreshVoxel) is how many frames the key lives; 0: for ever.
#ifdef MG_CACHE_REFRESH_UV
const uint kCacheRefreshUv = uint(MG_CACHE_REFRESH_UV);
#else
const uint kCacheRefreshUv = 0u;
#endif
#ifdef MG_CACHE_REFRESH_VOXEL
const uint kCacheRefreshVoxel = uint(MG_CACHE_REFRESH_VOXEL);
#else
const uint kCacheRefreshVoxel = 0u;
#endif
CacheKey cacheKeyOfHashes(uint h0, uint h1, uint refreshFrames) {
  // --cache-refresh N: a key lives N frames, then its cell is another key (an epoch in the
  // hashes), so the entry is filled again, at another point of the cell (cacheRefreshJitter),
  // and the old one ages out under the eviction. Each key's epochs start at its own phase
  // (H1 mod N), so a still camera refreshes 1/N of its entries a frame, not all of them every
  // N-th frame. Accumulated frames then average the cell's values instead of holding one
  // point of it (the voxel keys' point sample is otherwise fixed: seed 002 §3.2's aliasing).
  if (refreshFrames > 0u) {
    uint epoch = (frame.image.z + h1 % refreshFrames) / refreshFrames;
    uint epochHash = cachePcg(epoch ^ 0x5bd1e995u);
    h0 = cachePcg(h0 ^ epochHash);
    h1 = cachePcg(h1 ^ cachePcg(epochHash));
  }
  if (h1 == kCacheKeyEmpty) h1 = 1u;
  if (h1 == kCacheKeyLock) h1 = kCacheKeyLock - 1u;
  CacheKey key;
  key.base = h0 % (frame.cache.x - uint(MG_CACHE_PROBE));
  key.hash = h1;
  key.texelUv = vec2(0.0);
  key.texelSize = 0.0;
  return key;
}

// The point of its cell where a refreshed key is evaluated, in [0, 1)^3 of the cell: a hash
// of the key (which holds the epoch), so an entry is still its key's value whichever hit
// fills it, and each epoch takes a new point.
vec3 cacheRefreshJitter(CacheKey key) {
  uvec3 bits = uvec3(cachePcg(key.hash ^ 0x9e3779b9u), cachePcg(key.hash ^ 0x7f4a7c15u),
                     cachePcg(key.hash ^ 0x94d049bbu));
  return vec3(bits >> 8u) * (1.0 / 16777216.0);
}

// Eq. 5.8-5.10 for the cell (texel or tile) `cell` of level m. Cells are hashed by their
// float bits, which are exact for every magnitude (an int conversion would merge all cells
// past 2^31); -0 and +0 only give the same cell two entries. texelUv is the caller's.
CacheKey cacheKeyOf(uvec4 info, int m, vec2 cell) {
  uint u = floatBitsToUint(cell.x);
  uint v = floatBitsToUint(cell.y);
  // Eq. 5.8-5.9: two nested PCG hashes from two independent material ids.
  return cacheKeyOfHashes(cachePcg(uint(m) ^ cachePcg(u ^ cachePcg(v ^ info.y))),
                          cachePcg(uint(m) ^ cachePcg(u ^ cachePcg(v ^ info.z))),
                          kCacheRefreshUv);
}

// Voxel keys (MG_CACHE_CUTS) for cuts in object or world space, after seed 002 §3.1-3.2:
// a position is quantised to the voxel of level m that holds it, a cube 2^-m wide, so the
// voxel's integer coordinates are the position as a fixed-point number with m fractional
// bits (§3.1, Fig. 3: the sign in the most significant bit, the magnitude below; the level
// goes into the hash, so the same bits at two levels are two keys). Hashed like eq. 5.8-5.9:
// nested PCG hashes (§3.1's multidimensional hash, "a nested version of a PCG", Jarzynski and
// Olano 2020) of the object word, the three coordinates and the level, from the material's
// two independent ids; the slot is eq. 5.10. The value is the voxel centre's (§3.1, Fig. 2:
// the discrete position offset by half a voxel).
//
// The level follows the footprint as eq. 5.2-5.5 pick a texel level: the voxel about as wide
// as the shorter axis of the ray cone's footprint ellipse in the key's space, with the mip
// bias (positive: finer voxels). Levels stay within ±kCacheVoxelLevels, and a position whose
// voxel coordinate would not fit 31 bits bypasses the cache, as a non-finite uv does.
const float kCacheVoxelLevels = 20.0;
const float kCacheVoxelLimit = 1073741824.0;  // 2^30

uint cacheFixedPoint(float voxel) {
  return voxel < 0.0 ? 0x80000000u | uint(-voxel) : uint(voxel);
}

// A cell's point lies up to a cell off the surface, and a graph of the 3D position reads
// another value there than on the surface: the expectation of the cell's points is not what
// the surface shows. A box's side on the faces of its texture space, where a Brick's mortar
// reaches millimetres either side, shows mortar; the cell's points a cell off it show brick.
// Where the surface is a face perpendicular to an axis of the key's space (a box's sides,
// floors, walls, Blender's planes), the plane is known to within a fraction of a cell from
// the hit: the cell is a voxel's square across the face and a thin step along the axis, the
// key holds the axis and the step, and its points lie on the plane, still a function of the
// key, so an entry's value is the same whichever hit fills it. Elsewhere the cell is the
// voxel. The face is the footprint axes' plane (both lie in the hit's tangent plane) within
// kCacheFaceAlignment of the axis; the steps are 2^-kCacheFacePlaneBits of the voxel, centred
// on its multiples, so a plane at a round coordinate (0, 0.5, 1) is one step, evaluated on it.
const float kCacheFaceAlignment = 0.9999;  // cos 0.8 degrees
const float kCacheFacePlaneBits = 6.0;

// The axis + 1 to which the plane of footprint axes `axis1`, `axis2` is perpendicular, or 0.
uint cacheFaceAxis(vec3 axis1, vec3 axis2) {
  vec3 n = abs(cross(axis1, axis2));
  float largest = max(n.x, max(n.y, n.z));
  if (!(largest > 0.0) || !(largest >= kCacheFaceAlignment * length(n))) return 0u;
  return n.x == largest ? 1u : (n.y == largest ? 2u : 3u);
}

// The cell of level m that holds `p`: the voxel, or on a face (`face` != 0) the voxel's
// square across it and the plane's step along its axis.
vec3 cacheVoxelCell(vec3 p, int m, uint face) {
  vec3 cell = floor(p * exp2(float(m)));
  if (face != 0u)
    cell[face - 1u] = floor(p[face - 1u] * exp2(float(m) + kCacheFacePlaneBits) + 0.5);
  return cell;
}

// The point of cell `cell` (size `size`) at `at` in [0, 1)^3 of it (0.5: its centre); on a
// face, at the centre of the plane's step along the face's axis.
vec3 cacheVoxelPoint(vec3 cell, vec3 at, float size, uint face) {
  vec3 point = (cell + at) * size;
  if (face != 0u) point[face - 1u] = cell[face - 1u] * (size * exp2(-kCacheFacePlaneBits));
  return point;
}

// The key of cell `voxel` (integer coordinates, each within ±kCacheVoxelLimit) of level m on
// face `face` (0: none); `objectWord` the instance or mesh (0 for world space). The face goes
// into the level's word, flipping bits 24-25: a level within ±kCacheVoxelLevels varies only
// in bits 0-4 below its sign's extension, so no two (level, face) pairs share a word, and a
// face's cell and a voxel with the same coordinates are two keys.
CacheKey cacheVoxelKeyOf(uvec4 info, uint objectWord, int m, vec3 voxel, uint face) {
  uint x = cacheFixedPoint(voxel.x), y = cacheFixedPoint(voxel.y), z = cacheFixedPoint(voxel.z);
  uint h0 = cachePcg(objectWord ^ info.y);
  uint h1 = cachePcg(objectWord ^ info.z);
  uint level = uint(m) ^ (face << 24u);
  return cacheKeyOfHashes(cachePcg(level ^ cachePcg(z ^ cachePcg(y ^ cachePcg(x ^ h0)))),
                          cachePcg(level ^ cachePcg(z ^ cachePcg(y ^ cachePcg(x ^ h1)))),
                          kCacheRefreshVoxel);
}

// The voxel key of `p` with footprint axes `axis1`, `axis2` (a face's cell where they lie on
// one); `objectWord` the instance or mesh (0 for world space). `centre` and `size` are the
// cell's centre (with MG_CACHE_REFRESH_VOXEL this epoch's point of the cell: where its value is
// evaluated) and width; `widest`, where positive, the widest cell the key may take
// (cacheCellBound). False when the position is unusable (non-finite, or its voxel
// outside the fixed-point range).
bool cacheVoxelKeyFor(uvec4 info, uint objectWord, vec3 p, vec3 axis1, vec3 axis2,
                      float widest, out CacheKey key, out vec3 centre, out float size) {
  float lMin = min(length(axis1), length(axis2));
  float bias = uintBitsToFloat(frame.cache.z);
  float level = lMin > 0.0 ? -log2(lMin) + bias : kCacheVoxelLevels;
  if (widest > 0.0) level = max(level, ceil(-log2(widest)));
  int m = int(clamp(round(isnan(level) ? 0.0 : level), -kCacheVoxelLevels, kCacheVoxelLevels));
  size = exp2(-float(m));
  uint face = cacheFaceAxis(axis1, axis2);
  vec3 voxel = cacheVoxelCell(p, m, face);
  if (face != 0u && abs(voxel[face - 1u]) >= kCacheVoxelLimit) {  // the step past the range
    face = 0u;
    voxel = cacheVoxelCell(p, m, face);
  }
  centre = cacheVoxelPoint(voxel, vec3(0.5), size, face);
  key.base = 0u;
  key.hash = 0u;
  key.texelUv = vec2(0.0);
  key.texelSize = 0.0;
  if (isnan(level) || any(isnan(p)) || any(isinf(p)) ||
      any(greaterThanEqual(abs(voxel), vec3(kCacheVoxelLimit))))
    return false;
  key = cacheVoxelKeyOf(info, objectWord, m, voxel, face);
#ifdef MG_CACHE_REFRESH_VOXEL
  // This epoch's point of the cell (on a face, of its square on the plane).
  centre = cacheVoxelPoint(voxel, cacheRefreshJitter(key), size, face);
#endif
  return true;
}

// The footprint a voxel-centred evaluation runs with: one voxel along x and along y of the
// key's space (a float3_D carries two axes), whatever the hit's, so the value is the key's.
vec3 voxelAxis(uint axis, float size) {
  return axis == 0u ? vec3(size, 0.0, 0.0) : vec3(0.0, size, 0.0);
}

// Eq. 5.2-5.10 for the texel cache: the nearest texel of level m (eq. 5.6-5.7).
bool cacheKeyFor(uvec4 info, MaterialInputs inputs, out CacheKey key) {
  int m;
  bool usable = cacheMipLevel(inputs, m);
  vec2 texel = round(exp2(float(m)) * inputs.uv.v);
  key = cacheKeyOf(info, m, texel);
  key.texelSize = exp2(-float(m));
  key.texelUv = key.texelSize * texel;  // exact: a power of two times an integer
#ifdef MG_CACHE_REFRESH_UV
  // This epoch's point of the texel (eq. 5.6-5.7's texel spans its centre +- half a texel).
  key.texelUv += key.texelSize * (cacheRefreshJitter(key).xy - 0.5);
#endif
  return usable;
}

// Eq. 5.16-5.17: `inputs` at `uv` with the fictional footprint of one texel `texelSize` wide
// along u and along v instead of the hit's: how a texel's value is computed, so it does not
// depend on which hit asked first (the snapped texel cache and the tile cache).
MaterialInputs texelInputs(MaterialInputs inputs, vec2 uv, float texelSize) {
  inputs.uv.v = uv;
  inputs.uv.x = vec2(texelSize, 0.0);
  inputs.uv.y = vec2(0.0, texelSize);
  return inputs;
}

// Entry `entry`'s key word, and the first word of its record (after the S = frame.cache.x
// keys).
uint cacheKeyWord(uint entry) { return entry; }
uint cacheEntryOffset(uint entry) { return frame.cache.x + entry * kCacheRecordWords; }

// Largest finite half: fp16 stores clamp to it, so a bright emission becomes 65504 instead
// of an infinity that would poison the path.
const float kCacheHalfMax = 65504.0;

// Word w of a texel's stored values (kCacheValueWords words): one fp32 value, or two halves
// (an odd count leaves the last word's high half 0).
uint cacheValueWord(float values[MG_CACHE_VALUES], uint w) {
#ifdef MG_CACHE_VALUE_FP16
  uint i = 2u * w;
  float high = i + 1u < uint(MG_CACHE_VALUES) ? values[min(i + 1u, uint(MG_CACHE_VALUES) - 1u)]
                                              : 0.0;
  return packHalf2x16(clamp(vec2(values[i], high), vec2(-kCacheHalfMax), vec2(kCacheHalfMax)));
#else
  return floatBitsToUint(values[w]);
#endif
}

// The inverse: word w into `values`.
void cacheValueFromWord(uint word, uint w, inout float values[MG_CACHE_VALUES]) {
#ifdef MG_CACHE_VALUE_FP16
  vec2 pair = unpackHalf2x16(word);
  uint i = 2u * w;
  values[i] = pair.x;
  if (i + 1u < uint(MG_CACHE_VALUES)) values[min(i + 1u, uint(MG_CACHE_VALUES) - 1u)] = pair.y;
#else
  values[w] = uintBitsToFloat(word);
#endif
}

// Writes one texel's values at cacheData[wordOffset ..] as kCacheValueWords words.
void cacheStoreValues(uint wordOffset, float values[MG_CACHE_VALUES]) {
  for (uint w = 0u; w < kCacheValueWords; ++w) cacheStoreWord(wordOffset + w, cacheValueWord(values, w));
}

// Reads what cacheStoreValues wrote at cacheData[wordOffset ..].
void cacheLoadValues(uint wordOffset, out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  for (uint w = 0u; w < kCacheValueWords; ++w)
    cacheValueFromWord(cacheLoadValueWord(wordOffset + w), w, values);
}

// The clock (§5.3.3), advanced by `tick`: 1 for an access that stamps an entry's metadata,
// 0 to read what an entry's age is measured against. Frame clock: the host's frame number,
// the same for every access of a frame. Counter clock: a global 64-bit atomic counter, ticked
// by every stamping access and never reset between frames; the entry keeps bits
// MG_CACHE_CLOCK_SHIFT .. +31 of it ("only bits 16 to 48 of a 64-bit counter", §5.3.3). The
// kept 32 bits wrap (the frame clock after 2^32 frames, the counter clock after
// 2^(32 + shift) stamps), so ages are taken modulo 2^32 (cacheChooseSlot): correct across a
// wrap as long as no entry is older than 2^31 clock units.
uint cacheClock(uint tick) {
#ifdef MG_CACHE_CLOCK_COUNTER
  uint64_t ticks = atomicAdd(counters.cacheClock, uint64_t(tick));
  return uint(ticks >> uint(MG_CACHE_CLOCK_SHIFT));
#else
  return frame.cache.y;
#endif
}

// The ordering of the entry protocol (§5.3.4, a seqlock): a writer's lock must be visible
// before any of its value stores, and its value stores before the key that unlocks; a
// reader's first key load before its value loads, and those before its second key load.
// An acquire-release fence of device scope between each step: with the words on each side
// atomic (cacheLoadWord, cacheStoreWord, the lock's and unlock's exchanges), a writer's
// fence before its unlock synchronizes with a reader's fence after the load that saw the
// key, so the values are visible; and a reader that loaded a value of a later writer
// synchronizes with that writer's fence after its lock, so its second key (or counter) load
// sees the lock: the read is a miss. MakeAvailable and MakeVisible carry the image stores
// and loads of a tile in a storage image, which cannot be atomic (MG_CACHE_FENCE_STORAGE).
// Buffer-only where nothing lives in an image: a fence over image memory too would order
// the path tracer's texture reads on every lookup.
void cacheFence() {
  memoryBarrier(gl_ScopeDevice, MG_CACHE_FENCE_STORAGE,
                gl_SemanticsAcquireRelease | gl_SemanticsMakeAvailable | gl_SemanticsMakeVisible);
}

// The values an entry stores for output mask `mask`, in kCacheOutput* order.
void cachePack(uint mask, MaterialOutputs o, out float values[MG_CACHE_VALUES]) {
  uint n = 0u;
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  if ((mask & kCacheOutputBaseColor) != 0u) {
    values[n] = o.baseColor.x; values[n + 1u] = o.baseColor.y; values[n + 2u] = o.baseColor.z;
    n += 3u;
  }
  if ((mask & kCacheOutputMetallic) != 0u) { values[n] = o.metallic; n += 1u; }
  if ((mask & kCacheOutputRoughness) != 0u) { values[n] = o.roughness; n += 1u; }
  if ((mask & kCacheOutputNormal) != 0u) {
    values[n] = o.normal.x; values[n + 1u] = o.normal.y; values[n + 2u] = o.normal.z;
    n += 3u;
  }
  if ((mask & kCacheOutputEmission) != 0u) {
    values[n] = o.emission.x; values[n + 1u] = o.emission.y; values[n + 2u] = o.emission.z;
    n += 3u;
  }
  if ((mask & kCacheOutputOpacity) != 0u) { values[n] = o.opacity; n += 1u; }
  if ((mask & kCacheOutputSpecular) != 0u) { values[n] = o.specular; n += 1u; }
  if ((mask & kCacheOutputSpecularTint) != 0u) {
    values[n] = o.specularTint;
    n += 1u;
  }
  if ((mask & kCacheOutputCyclesPrincipled) != 0u) {
    values[n] = o.cyclesPrincipled;
    n += 1u;
  }
#ifndef MG_OMIT_BSDF_LOBES
  if ((mask & kCacheOutputLobes) != 0u) {
    values[n] = float(o.lobeCount);
    for (uint i = 0u; i < uint(MG_MAX_LOBES); ++i) {
      uint at = n + 1u + 6u * i;
      values[at] = o.lobeWeight[i].x; values[at + 1u] = o.lobeWeight[i].y;
      values[at + 2u] = o.lobeWeight[i].z; values[at + 3u] = o.lobeWeight[i].w;
      values[at + 4u] = o.lobeParameters[i].x; values[at + 5u] = o.lobeParameters[i].y;
    }
    n += kCacheLobeValues;
  }
  if ((mask & kCacheOutputLobeNormals) != 0u) {
    for (uint i = 0u; i < uint(MG_MAX_LOBES); ++i) {
      values[n + 2u * i] = o.lobeParameters[i].z;
      values[n + 2u * i + 1u] = o.lobeParameters[i].w;
    }
    n += kCacheLobeNormalValues;
  }
#endif
}

// Outputs from cached values: the members the graph writes from the entry, the rest as the
// graph would leave them (mg_defaultMaterialOutputs of this hit: its own geometric normal).
MaterialOutputs cacheUnpack(uint mask, float values[MG_CACHE_VALUES], MaterialInputs inputs) {
  MaterialOutputs o = mg_defaultMaterialOutputs(inputs);
  uint n = 0u;
  if ((mask & kCacheOutputBaseColor) != 0u) {
    o.baseColor = vec3(values[n], values[n + 1u], values[n + 2u]);
    n += 3u;
  }
  if ((mask & kCacheOutputMetallic) != 0u) { o.metallic = values[n]; n += 1u; }
  if ((mask & kCacheOutputRoughness) != 0u) { o.roughness = values[n]; n += 1u; }
  if ((mask & kCacheOutputNormal) != 0u) {
    o.normal = vec3(values[n], values[n + 1u], values[n + 2u]);
    n += 3u;
  }
  if ((mask & kCacheOutputEmission) != 0u) {
    o.emission = vec3(values[n], values[n + 1u], values[n + 2u]);
    n += 3u;
  }
  if ((mask & kCacheOutputOpacity) != 0u) { o.opacity = values[n]; n += 1u; }
  if ((mask & kCacheOutputSpecular) != 0u) { o.specular = values[n]; n += 1u; }
  if ((mask & kCacheOutputSpecularTint) != 0u) {
    o.specularTint = values[n];
    n += 1u;
  }
  if ((mask & kCacheOutputCyclesPrincipled) != 0u) {
    o.cyclesPrincipled = values[n];
    n += 1u;
  }
#ifndef MG_OMIT_BSDF_LOBES
  // A filtered entry blends several entries' lobes: the same kinds in the same order
  // (mg_addLobe), so the count and kinds come back whole; rounded against float error.
  if ((mask & kCacheOutputLobes) != 0u) {
    o.lobeCount = int(round(values[n]));
    for (uint i = 0u; i < uint(MG_MAX_LOBES); ++i) {
      uint at = n + 1u + 6u * i;
      o.lobeWeight[i] = vec4(values[at], values[at + 1u], values[at + 2u], round(values[at + 3u]));
      o.lobeParameters[i] = vec4(values[at + 4u], values[at + 5u], 0.0, 0.0);
    }
    n += kCacheLobeValues;
  }
  // A filtered entry blends the lobes' octahedral normals: nearby normals, as the material's
  // normal is blended. A lobe without one stores (0, 0) in every entry and keeps it.
  if ((mask & kCacheOutputLobeNormals) != 0u) {
    for (uint i = 0u; i < uint(MG_MAX_LOBES); ++i) {
      o.lobeParameters[i].z = values[n + 2u * i];
      o.lobeParameters[i].w = values[n + 2u * i + 1u];
    }
    n += kCacheLobeNormalValues;
  }
#endif
  return o;
}

// §5.3.3: linear search over D entries comparing only keys; the entry index or -1. The D
// keys are loaded before any is compared, so the loads are independent and in flight
// together. Compared as each arrives, a hit at probe d could wait for d + 1 loads one after
// another (a compiler need not speculate a coherent load past the branch), and in a full
// cache LRU puts keys anywhere in the range.
int cacheFind(CacheKey key) {
  uint stored[MG_CACHE_PROBE];
  [[unroll]] for (uint d = 0u; d < uint(MG_CACHE_PROBE); ++d)
    stored[d] = cacheLoadKeyWord(cacheKeyWord(key.base + d));
  int found = -1;
  [[unroll]] for (uint d = 0u; d < uint(MG_CACHE_PROBE); ++d) {
    if (found < 0 && stored[d] == key.hash) found = int(key.base + d);
  }
  return found;
}

// §5.3.4: a read is key, values, key again, and a miss if the key changed meanwhile. With
// the update counter: counter, key, values, key and counter again; a miss if either changed
// (a write in between bumped the counter even when it restored the key). cacheReadBegin
// comes after the key matched and before the values are loaded; it returns the counter
// (0 without one) or kCacheKeyLock when the key already changed.
uint cacheReadBegin(uint entry, CacheKey key) {
  uint counterBefore = 0u;
#ifndef MG_CACHE_QUIESCENT_READS  // otherwise nothing writes the values: nothing to check
#ifdef MG_CACHE_UPDATE_COUNTER
  uint offset = cacheEntryOffset(entry);
  cacheFence();
  counterBefore = cacheLoadWord(offset + kCacheCounterWord);
  cacheFence();
  if (cacheLoadWord(cacheKeyWord(entry)) != key.hash) return kCacheKeyLock;
#endif
  cacheFence();  // key, then values
#endif
  return counterBefore;
}

// A read's stamp of an entry's clock word at `offset` (lru, §5.3.3): stored only when it
// changes. The counter clock keeps bits MG_CACHE_CLOCK_SHIFT.. of the count, so the hits of a
// texel close together in time give it the same stamp, and a stored word equal to the new
// one is the same LRU order. On the H200 the unconditional store cost 28 of the wavefront
// lookup pass's 43 ms (classroom 1080p, P = 6, L = 4: 47.9 M hits a frame, each a store into
// a 671 MB table; with the frame clock, which already stored only a change, 15 ms).
void cacheStamp(uint offset, uint stamp) {
  if (cacheLoadWord(offset + kCacheClockWord) != stamp) cacheStoreWord(offset + kCacheClockWord, stamp);
}

#if defined(MG_CACHE_STAMP_BY_SUBGROUP) && MG_CACHE_EVICTION == 1 && \
    defined(MG_CACHE_CLOCK_COUNTER)
// Under lru with the counter clock every hit ticks the one global clock: an atomic on one
// address per hit. Here a read's stamp waits for cacheStampReads, which ticks the clock once
// for all of a subgroup's hits and gives each its own tick in lane order: the same count of
// ticks, the same clock, one atomic per subgroup. (On the H200 this alone left the lookup
// pass at 43.3 ms against 44.5: the stamp's store, not the atomic, was the cost; cacheStamp.)
#define MG_CACHE_DEFERRED_STAMP 1
const uint kCacheNoStamp = 0xFFFFFFFFu;
uint g_cacheStampOffset = kCacheNoStamp;  // the entry whose stamp waits, if any

// Stamps the entries this subgroup's reads found. Every invocation of the subgroup calls it.
void cacheStampReads() {
  uint tick = g_cacheStampOffset != kCacheNoStamp ? 1u : 0u;
  uint total = subgroupAdd(tick);
  if (total == 0u) return;  // uniform
  uint rank = subgroupExclusiveAdd(tick);
  uvec2 first = uvec2(0u);
  if (subgroupElect()) first = unpackUint2x32(atomicAdd(counters.cacheClock, uint64_t(total)));
  first = uvec2(subgroupAdd(first.x), subgroupAdd(first.y));  // the elected one's, to all
  if (tick != 0u) {
    uint64_t ticks = packUint2x32(first) + uint64_t(rank);
    cacheStamp(g_cacheStampOffset, uint(ticks >> uint(MG_CACHE_CLOCK_SHIFT)));
    g_cacheStampOffset = kCacheNoStamp;
  }
}
#else
void cacheStampReads() {}
#endif

// After the values were loaded: true when they belong to the key (see cacheReadBegin).
// Under lru a valid read refreshes the entry's clock (§4.5, §5.3.3).
bool cacheReadValid(uint entry, CacheKey key, uint counterBefore) {
  uint offset = cacheEntryOffset(entry);
#ifndef MG_CACHE_QUIESCENT_READS
#ifdef MG_CACHE_UPDATE_COUNTER
  if (counterBefore == kCacheKeyLock) return false;
#endif
  cacheFence();  // values, then the second key load
  if (cacheLoadWord(cacheKeyWord(entry)) != key.hash) return false;  // overwritten while reading
#ifdef MG_CACHE_UPDATE_COUNTER
  if (cacheLoadWord(offset + kCacheCounterWord) != counterBefore) return false;  // key restored
#endif
#endif
#if MG_CACHE_EVICTION == 1  // kCacheEvictionLru
#if defined(MG_CACHE_DEFERRED_STAMP)
  // A second read before cacheStampReads stamps the first at once.
  if (g_cacheStampOffset != kCacheNoStamp) cacheStamp(g_cacheStampOffset, cacheClock(1u));
  g_cacheStampOffset = offset;
#elif defined(MG_CACHE_CLOCK_COUNTER)
  cacheStamp(offset, cacheClock(1u));  // §5.3.3: reads count only for lru
#else
  cacheStamp(offset, frame.cache.y);
#endif
#endif
  return true;
}

// The texel cache's read: the values of `key`, or false on a miss.
bool cacheRead(CacheKey key, out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  int entry = cacheFind(key);
  if (entry < 0) return false;
  uint counterBefore = cacheReadBegin(uint(entry), key);
  cacheLoadValues(cacheEntryOffset(uint(entry)) + kCacheHeader, values);
  return cacheReadValid(uint(entry), key, counterBefore);
}

// The eviction policy's slot in the probe range (§4.5, §5.3.3), or -1 for "do not insert".
// Empty entries are taken first by every policy; then none drops the value, lru and lrw
// take the oldest frame clock (lru's is refreshed by reads, lrw's only by writes), random
// a pseudo-random entry (a hash of the key and the frame: no memory access, §4.5). The
// clock compared is the frame clock or the counter clock's kept bits (cacheClock).
int cacheChooseSlot(CacheKey key) {
  int oldest = -1;
#if MG_CACHE_EVICTION == 1 || MG_CACHE_EVICTION == 2
  uint now = cacheClock(0u);
  uint oldestAge = 0u;
#endif
  bool besideALock = false;  // counted (g_locksBesideALock) when a slot is chosen
  [[unroll]] for (uint d = 0u; d < uint(MG_CACHE_PROBE); ++d) {
    uint stored = cacheLoadWord(cacheKeyWord(key.base + d));
    if (stored == kCacheKeyEmpty) {
      if (besideALock) g_locksBesideALock += 1u;
      return int(d);
    }
    if (stored == kCacheKeyLock) besideALock = true;
#if MG_CACHE_EVICTION == 1 || MG_CACHE_EVICTION == 2
    if (stored != kCacheKeyLock) {
      // Age modulo 2^32: after the clock wraps, the newest stamps are small numbers but
      // small ages (comparing the stamps themselves evicted the newest entries first).
      uint age = now - cacheLoadWord(cacheEntryOffset(key.base + d) + kCacheClockWord);
      if (oldest < 0 || age > oldestAge) {
        oldestAge = age;
        oldest = int(d);
      }
    }
#endif
  }
#if MG_CACHE_EVICTION == 3
  oldest = int(cachePcg(key.hash ^ cachePcg(frame.cache.y)) % uint(MG_CACHE_PROBE));
#endif
  if (besideALock && oldest >= 0) g_locksBesideALock += 1u;
  return oldest;
}

// §5.3.4: picks the eviction policy's entry for `key` and locks it with an atomic exchange
// to kCacheKeyLock. Returns the entry, or -1 when the policy declines or the entry is
// already locked (not retried: the value is used by this thread but not cached); `evicted`
// is the key the entry held (kCacheKeyEmpty if none), whose values and clock stay in the
// entry until the locker stores its own (cacheRestore gives them back). Locking an empty
// entry counts it as occupied: a key never returns to empty, so the count only grows and
// stays at most S.
int cacheLockEvicting(CacheKey key, out uint evicted) {
  evicted = kCacheKeyEmpty;
  int slot = cacheChooseSlot(key);
  if (slot < 0) return -1;
  uint entry = key.base + uint(slot);
  uint offset = cacheEntryOffset(entry);
#if MG_CACHE_EVICTION == 0  // kCacheEvictionNone
  // Only an entry still empty: between cacheChooseSlot's read and the lock another
  // invocation may have locked it and published its key, which an exchange would evict (a
  // tile computed into an entry that counted no new occupant, seen on lavapipe).
  uint previous = cacheCompareExchangeWord(cacheKeyWord(entry), kCacheKeyEmpty, kCacheKeyLock);
  if (previous != kCacheKeyEmpty) {
    g_locksContended += 1u;
    return -1;
  }
#else
  uint previous = cacheExchangeWord(cacheKeyWord(entry), kCacheKeyLock);
  if (previous == kCacheKeyLock) {
    g_locksContended += 1u;
    return -1;
  }
#endif
  evicted = previous;
  if (previous == kCacheKeyEmpty) atomicAdd(counters.cacheOccupancy, 1u);
#ifdef MG_CACHE_UPDATE_COUNTER
  cacheAddWord(offset + kCacheCounterWord, 1u);  // before any value changes (§5.3.4)
#endif
  // The lock (and the counter) before any value store, in both read-check modes: without
  // this fence a reader could see the old key around new values (the key mode had none).
  cacheFence();
  return int(entry);
}

int cacheLock(CacheKey key) {
  uint evicted;
  return cacheLockEvicting(key, evicted);
}

// After the values of a locked entry were written: its clock, then the key, which
// unlocks it.
void cacheUnlock(uint entry, CacheKey key) {
  uint offset = cacheEntryOffset(entry);
#if MG_CACHE_EVICTION == 1 || MG_CACHE_EVICTION == 2
  cacheStoreWord(offset + kCacheClockWord, cacheClock(1u));
#else
  cacheStoreWord(offset + kCacheClockWord, frame.cache.y);  // unread by none and random
#endif
  cacheFence();  // the values (buffer or image) and the clock, then the key
  cacheExchangeWord(cacheKeyWord(entry), key.hash);
}

// Gives up a locked entry without a value: empty again, and one fewer occupied entry (a
// locked entry counts as occupied, whether it was locked from empty, which counted it, or
// from an evicted key, whose values are gone now). On NVIDIA's raygen the tile cache gives
// up hundreds of thousands of entries a frame (callable repacks); without this the
// occupancy overstated S threefold.
void cacheUnlockEmpty(uint entry) {
  cacheExchangeWord(cacheKeyWord(entry), kCacheKeyEmpty);
  atomicAdd(counters.cacheOccupancy, 0xFFFFFFFFu);  // minus one
}

// Gives up a locked entry whose values this lock never touched: the key it held before
// (`evicted`, from cacheLockEvicting) goes back, with the values and the clock it kept, or the
// entry goes back empty when it had none (cacheUnlockEmpty). Emptying an evicted entry
// instead threw away a cached tile that nothing replaced, and on NVIDIA's raygen callable
// repacks give up most tiles started (H200, classroom 1080p, 2^17 tiles, lrw counter: about
// 586,000 tiles started and 211,000 published a frame). Readers stay safe: the restored key's
// values are the ones its writer published, and every store to a key word is an atomic
// read-modify-write, so a reader that sees the key again synchronizes with that writer; with
// the update counter the lock's bump makes a read across the lock miss.
void cacheRestore(uint entry, uint evicted) {
  if (evicted == kCacheKeyEmpty) {
    cacheUnlockEmpty(entry);
    return;
  }
  cacheFence();
  cacheExchangeWord(cacheKeyWord(entry), evicted);
}

// The texel cache's insert: lock, values, unlock.
void cacheWrite(CacheKey key, float values[MG_CACHE_VALUES]) {
  int entry = cacheLock(key);
  if (entry < 0) return;
  cacheStoreValues(cacheEntryOffset(uint(entry)) + kCacheHeader, values);
  cacheUnlock(uint(entry), key);
}

#ifdef MG_CACHE_CUTS
// Scene material `materialId`'s cut key (mg_materialCutInfo; none past the scene's).
uvec4 cutInfoOf(uint materialId) {
  return materialId < uint(mg_materialCutInfo.length()) ? mg_materialCutInfo[materialId]
                                                        : uvec4(0u);
}

// The inputs a voxel key's cut is evaluated with: the voxel's centre, with the footprint of
// one voxel along x and y of its space, so the value is the key's whichever hit asks.
// `domain` kCacheCutWorld or kCacheCutObject, `object` the hit's (instance, mesh).
MaterialInputs voxelKeyInputs(uint domain, MaterialInputs inputs, uvec2 object, vec3 centre,
                              float size) {
  MaterialInputs keyInputs = inputs;
  if (domain == kCacheCutWorld) {
    keyInputs.position.v = centre;
    keyInputs.position.x = voxelAxis(0u, size);
    keyInputs.position.y = voxelAxis(1u, size);
  }
#ifndef MG_OMIT_OBJECT_INPUTS  // an object-space cut reads them, so they are there
  else {
    // Generated is affine in the object-space position (path_shading.glsl surfaceAt): the
    // same map at the centre, and its footprint the voxel's through the same scale. Computed
    // from the centre alone, not moved from the hit's, so an entry's value is the same to the
    // bit whichever hit filled it (moved, it differed by float rounding from run to run).
    vec3 toGenerated = 0.5 / meshes[object.y].textureSpaceSize.xyz;
    keyInputs.objectPosition.v = centre;
    keyInputs.objectPosition.x = voxelAxis(0u, size);
    keyInputs.objectPosition.y = voxelAxis(1u, size);
    keyInputs.generated.v =
        (centre - meshes[object.y].textureSpaceLocation.xyz) * toGenerated + 0.5;
    keyInputs.generated.x = keyInputs.objectPosition.x * toGenerated;
    keyInputs.generated.y = keyInputs.objectPosition.y * toGenerated;
    keyInputs.generatedScale = toGenerated;
  }
#endif
  return keyInputs;
}

// The instance where the graph reads Object Info's per-instance members, else the mesh:
// object-space values are the mesh's (Generated needs its texture space), shared by its
// instances. Materials sharing a graph share one choice, so the two never mix.
uint cutObjectWord(uvec4 cut, uvec2 object) { return cut.z != 0u ? object.x : object.y; }

// The widest cell a voxel key may take at world position p of the hit's `object`, in world
// units, or with `objectUnits` in the object's. A voxel's point fills its cell's volume, up
// to a cell off the surface, and a wide cone (a diffuse bounce's) asks for a cell as wide as
// the object: its one point, far inside or outside the object, where Generated coordinates
// leave the texture space and bands or ramps take other values, then stands for all of it.
// So a cell is no wider than 1/kCacheObjectCells of the object (the largest side of its
// mesh's texture space, times its instance's largest axis scale), unless the cell a camera
// ray would take at the hit is wider (a pixel at its distance, scaled by the mip bias as
// every footprint is): what the camera cannot resolve there keeps cells of that width, so a
// small object far away is not keyed finer than its pixels, which would leave nothing to
// find again, and a coarser mip bias still coarsens. Chosen on an H100 (the Blender material
// scene's object keys, 1536 samples a pixel, refresh 16, without the pixel): the still
// camera's 8x8-block error 0.0027 without the bound, 0.0010 at 1/64, 0.0009 at 1/128 and
// 0.0006 at 1/256, against a seed-to-seed 0.0009; the frame 43.9, 44.3, 44.8 and 45.6 ms
// (docs/design/memoization.md, "Where the cached picture differs").
const float kCacheObjectCells = 256.0;

float cacheCellBound(uvec2 object, vec3 p, bool objectUnits) {
  vec3 halfSize = meshes[object.y].textureSpaceSize.xyz;
  mat4 toWorld = instances[object.x].objectToWorld;
  float scale =
      max(length(toWorld[0].xyz), max(length(toWorld[1].xyz), length(toWorld[2].xyz)));
  float objectCell =
      2.0 * max(halfSize.x, max(halfSize.y, halfSize.z)) * scale / kCacheObjectCells;
  float cameraCell = frame.cameraPosition.w * distance(p, frame.cameraPosition.xyz) *
                     exp2(-uintBitsToFloat(frame.cache.z));
  float widest = max(objectCell, cameraCell);
  return objectUnits ? widest / scale : widest;
}

// The key of a material's cut at a hit, and the inputs its cut is evaluated with on a miss
// (thesis §7: memoize the part of the graph one key determines; compiler/cut.h; the voxel
// keys of seed 002 §3.1-3.2): the uv texel's centre with one texel along u and v (eq.
// 5.16-5.17), or the voxel's centre with one voxel along x and y of its space
// (voxelKeyInputs), so an entry holds its key's value whichever hit filled it, and a cached
// value is a function of the key. One function for both architectures (the megakernel's
// evaluateMaterialThroughCut and the wavefront's lookup and material passes), so both key a
// hit alike and fill the same values. `info` is the material's mg_materialCacheInfo (its
// ids), `cut` its mg_materialCutInfo, `object` the hit's (instance, mesh). False when the hit
// has no usable key (non-finite coordinates or a voxel outside the fixed-point range): the hit
// then runs uncached.
bool cacheCutKeyFor(uvec4 info, uvec4 cut, uvec2 object, MaterialInputs inputs,
                    out CacheKey key, out MaterialInputs keyInputs) {
  keyInputs = inputs;
  bool usable = false;
  if (cut.x == kCacheCutUv) {
    usable = cacheKeyFor(info, inputs, key);
    keyInputs = texelInputs(inputs, key.texelUv, key.texelSize);
  } else if (cut.x == kCacheCutWorld) {
    vec3 centre;
    float size;
    usable = cacheVoxelKeyFor(info, 0u, inputs.position.v, inputs.position.x, inputs.position.y,
                              cacheCellBound(object, inputs.position.v, false), key, centre,
                              size);
    keyInputs = voxelKeyInputs(kCacheCutWorld, inputs, object, centre, size);
  }
#ifndef MG_OMIT_OBJECT_INPUTS
  else if (cut.x == kCacheCutObject) {
    vec3 centre;
    float size;
    usable = cacheVoxelKeyFor(info, cutObjectWord(cut, object), inputs.objectPosition.v,
                              inputs.objectPosition.x, inputs.objectPosition.y,
                              cacheCellBound(object, inputs.position.v, true), key, centre, size);
    keyInputs = voxelKeyInputs(kCacheCutObject, inputs, object, centre, size);
  }
#endif
  else {
    key.base = 0u;
    key.hash = 0u;
    key.texelUv = vec2(0.0);
    key.texelSize = 0.0;
  }
  return usable;
}
#endif  // MG_CACHE_CUTS

// The wavefront splits this into its lookup pass and its material passes (wavefront.glsl);
// its material passes run it in place for filtered reads and for cuts too wide for its path
// state, with their own evaluateMaterialDirect and cut and rest functions (the texel cache's
// only: the tile cache includes this file for its entry protocol alone).
#if !defined(MG_WAVEFRONT) || (defined(MG_WAVEFRONT_MATERIAL) && defined(MG_CACHE_TEXEL))
// Cacheable materials (mask != 0) read the cache and on a miss evaluate and insert; with
// MG_CACHE_CUTS, a material with a cut is keyed by it (evaluateMaterialThroughCut); others
// are evaluated directly and never touch the cache. With MG_CACHE_SNAP_UV a miss
// evaluates at the texel centre (§6.1: "rounding the texture coordinates to the nearest
// cache texel before evaluating") with the fictional derivatives of one texel along u and v
// (eq. 5.16-5.17, as the tile cache computes its texels), so an entry holds its texel's
// value, not that of whichever hit inside the texel came first (its footprint picks an image
// texture's mip level); this hit then shades with that value too.

#ifdef MG_CACHE_FILTER
// Filtering (docs/design/memoization.md, "Filtering"). Nearest reads the one entry whose
// texel (eq. 5.6-5.7) or voxel (seed 002 §3.1) holds the hit, at the level round(L) of the
// continuous level L = -log2(l_min) + bias (eq. 5.5): where a texel, voxel or level boundary
// crosses a surface the value steps. Thesis §7 proposes trilinear interpolation between mip
// levels: at levels floor(L) and floor(L) + 1 the entries whose centres surround the hit (2x2
// texels, 2x2x2 voxels), bilinearly (trilinearly) weighted in each level and linearly across
// the two, each entry evaluated at its centre on a miss. MG_CACHE_FILTER ==
// kCacheFilterTrilinear reads all of them and blends; kCacheFilterStochastic reads one, picked
// with its weight as probability (seed 002 §3.2's random selection by weight, instead of its
// Fig. 9a jitter; for fixed cells the two are the same: jittering the point uniformly by up to
// half a cell and taking the cell that holds it picks a cell with its linear weight). Its
// expectation is the trilinear value, so the step averages out under accumulation at the cost
// of one lookup, not 8 or 16.

// The stochastic pick's random numbers: path_tracer.glsl sets the key before each material
// evaluation from the path vertex's (pixel, sample, bounce, seed), so the picks repeat per seed
// and differ per sample; hashed once more so they are not the vertex's shading numbers.
uint g_cacheFilterKey = 0u;
uint g_cacheFilterDimension = 0u;

// Seeds the stochastic picks of path vertex `vertex` (bounce + 1 for the bounce-th hit, the
// shading key of rng.glsl) of sample `sampleIndex` of pixel `pixelIndex`: both architectures
// call it before a material evaluation, so at one seed they pick the same entries.
void cacheSeedFilterPicks(uint pixelIndex, uint sampleIndex, uint vertex, uint seed) {
  g_cacheFilterKey = pcgHash(rngForPathVertex(pixelIndex, sampleIndex, vertex, seed).key ^
                             0x9E3779B9u);
}

float cacheFilterRandom() {
  uint word = cachePcg(g_cacheFilterKey ^ cachePcg(g_cacheFilterDimension));
  g_cacheFilterDimension += 1u;
  return float(word >> 8u) * (1.0 / 16777216.0);
}

// Where a filtered lookup reads a key space: the hit's position in it (uv: z = 0), the
// cells' place (cell k's centre lies at (k + centreOffset) 2^-m: 0 for texels, which round,
// 0.5 for voxels, which floor), the coarser level and the finer level's weight.
struct CacheFilterSite {
  vec3 position;
  uint dimensions;  // 2 (uv texels) or 3 (voxels)
  uint face;        // voxels on a face: its axis + 1 (cacheFaceAxis), else 0
  float centreOffset;
  int coarseLevel;    // floor(L); the finer level is coarseLevel + 1
  float fineWeight;   // L - floor(L)
};

// The coarse level and the weight of the fine one for the continuous level `level` within
// ±`range` (the nearest filter's clamp).
void cacheFilterLevels(float level, float range, inout CacheFilterSite site) {
  float clamped = clamp(level, -range, range);
  site.coarseLevel = int(min(floor(clamped), range - 1.0));
  site.fineWeight = clamped - float(site.coarseLevel);
}

// The uv site of a hit, with cacheMipLevel's level unrounded. False where cacheMipLevel's is.
bool cacheUvFilterSite(MaterialInputs inputs, out CacheFilterSite site) {
  vec2 uv = inputs.uv.v;
  float lMin = min(length(inputs.uv.x), length(inputs.uv.y));
  float bias = uintBitsToFloat(frame.cache.z);
  float level = lMin > 0.0 ? -log2(lMin) + bias : 24.0;
  site.position = vec3(uv, 0.0);
  site.dimensions = 2u;
  site.face = 0u;
  site.centreOffset = 0.0;
  site.coarseLevel = 0;
  site.fineWeight = 0.0;
  if (isnan(level) || any(isnan(uv)) || any(isinf(uv))) return false;
  cacheFilterLevels(level, 24.0, site);
  return true;
}

// The voxel site of position `p` with footprint axes `axis1`, `axis2`, with
// cacheVoxelKeyFor's level unrounded and its face (where the finer level's step along the
// face's axis is within the fixed-point range). False when p is not finite or a voxel of the
// finer level around it (one past floor on each axis) is outside the fixed-point range.
bool cacheVoxelFilterSite(vec3 p, vec3 axis1, vec3 axis2, out CacheFilterSite site) {
  float lMin = min(length(axis1), length(axis2));
  float bias = uintBitsToFloat(frame.cache.z);
  float level = lMin > 0.0 ? -log2(lMin) + bias : kCacheVoxelLevels;
  site.position = p;
  site.dimensions = 3u;
  site.face = cacheFaceAxis(axis1, axis2);
  site.centreOffset = 0.5;
  site.coarseLevel = 0;
  site.fineWeight = 0.0;
  if (isnan(level) || any(isnan(p)) || any(isinf(p))) return false;
  cacheFilterLevels(level, kCacheVoxelLevels, site);
  if (site.face != 0u &&
      abs(cacheVoxelCell(p, site.coarseLevel + 1, site.face)[site.face - 1u]) >= kCacheVoxelLimit)
    site.face = 0u;
  vec3 fine = floor(p * exp2(float(site.coarseLevel + 1)) - 0.5);
  return all(lessThan(abs(fine) + 1.0, vec3(kCacheVoxelLimit)));
}

// Entries a filtered lookup reads at most: both levels' 2^dimensions cells, or one.
uint cacheFilterEntryCount(CacheFilterSite site) {
#if MG_CACHE_FILTER == 1  // kCacheFilterTrilinear
  return 2u << site.dimensions;
#else
  return 1u;
#endif
}

// Entry `index` (< cacheFilterEntryCount) of the filter at `site`: its level m, its cell
// (integer coordinates at m; z = 0 for uv) and its weight. Trilinear: index bits are the cell's
// corner per axis, then the level; the weight is the product of the linear weights. Stochastic:
// the level, then the corner on each axis, drawn with their linear weights as probabilities, so
// the entry comes with the trilinear weight as its probability and counts with weight 1. On a
// face the cells are its squares (bilinear in each level), all at the plane's step.
void cacheFilterEntry(CacheFilterSite site, uint index, out int m, out vec3 cell,
                      out float weight) {
#if MG_CACHE_FILTER == 1
  uint fine = index >> site.dimensions;
#else
  uint fine = cacheFilterRandom() < site.fineWeight ? 1u : 0u;
#endif
  m = site.coarseLevel + int(fine);
  vec3 t = site.position * exp2(float(m)) - site.centreOffset;
  vec3 lower = floor(t);
  vec3 f = t - lower;  // 0 in z for uv (position.z = 0, offset 0)
  if (site.face != 0u) f[site.face - 1u] = 0.0;  // one cell along a face's axis
#if MG_CACHE_FILTER == 1
  vec3 corner = vec3(uvec3(index, index >> 1u, site.dimensions == 3u ? index >> 2u : 0u) & 1u);
  vec3 axisWeights = mix(1.0 - f, f, corner);
  weight = axisWeights.x * axisWeights.y * axisWeights.z *
           (fine != 0u ? site.fineWeight : 1.0 - site.fineWeight);
#else
  vec3 corner = vec3(cacheFilterRandom() < f.x ? 1.0 : 0.0, cacheFilterRandom() < f.y ? 1.0 : 0.0,
                     cacheFilterRandom() < f.z ? 1.0 : 0.0);
  weight = 1.0;
#endif
  cell = lower + corner;
  if (site.face != 0u)
    cell[site.face - 1u] = cacheVoxelCell(site.position, m, site.face)[site.face - 1u];
}

// One entry of a filtered lookup: its values, read, or on a miss evaluated at `keyInputs` (its
// centre) — the cut with `throughCut`, else the whole material packed — and inserted under the
// usual protocol (cacheRead, cacheWrite). Counted as one lookup.
void cacheReadOrFill(uint materialId, uvec4 info, bool throughCut, CacheKey key,
                     MaterialInputs keyInputs, out float values[MG_CACHE_VALUES]) {
  g_cacheLookups += 1u;
  if (cacheRead(key, values)) {
    g_cacheHits += 1u;
    return;
  }
  g_cacheMisses += 1u;
  g_cacheMissed = true;
#ifdef MG_CACHE_CUTS
  if (throughCut) {
    evaluateMaterialCutSwitch(materialId, keyInputs, values);
  } else
#endif
  {
#ifndef MG_CACHE_CUT_PASS  // a wavefront cut pass fills cut entries only
    MaterialOutputs outputs;
    evaluateMaterialDirect(materialId, keyInputs, outputs);
    cachePack(info.x, outputs, values);
#endif
  }
  cacheWrite(key, values);
}

// The filtered values at `site` of a uv key (`domain` kCacheCutUv, or kCacheCutNone for a
// whole material) or a voxel key (kCacheCutWorld, kCacheCutObject with `objectWord`).
void cacheFilteredValues(uint materialId, uvec4 info, uint domain, uint objectWord,
                         uvec2 object, MaterialInputs inputs, CacheFilterSite site,
                         out float blended[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) blended[i] = 0.0;
  g_cacheFilterDimension = 0u;
  uint count = cacheFilterEntryCount(site);
  for (uint index = 0u; index < count; ++index) {
    int m;
    vec3 cell;
    float weight;
    cacheFilterEntry(site, index, m, cell, weight);
    if (weight == 0.0) continue;  // the hit lies on the cell's far edge or a level exactly
    float size = exp2(-float(m));
    CacheKey key;
    MaterialInputs keyInputs;
#ifdef MG_CACHE_CUTS
    if (site.dimensions == 3u) {
      key = cacheVoxelKeyOf(info, objectWord, m, cell, site.face);
      keyInputs = voxelKeyInputs(domain, inputs, object,
                                 cacheVoxelPoint(cell, vec3(0.5), size, site.face), size);
    } else
#endif
    {
      key = cacheKeyOf(info, m, cell.xy);
      keyInputs = texelInputs(inputs, cell.xy * size, size);  // exact: 2^-m times an integer
    }
    float values[MG_CACHE_VALUES];
    cacheReadOrFill(materialId, info, domain != kCacheCutNone, key, keyInputs, values);
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) blended[i] += weight * values[i];
  }
}
#endif  // MG_CACHE_FILTER

#ifdef MG_CACHE_CUTS
// The unfiltered read of a cut's entry at a hit, counted as one lookup: true with `values`
// read. `keyed` comes in as whether the hit may take a key (the cache on for this frame and
// bounce) and goes out as whether it has one (cacheCutKeyFor); `keyInputs` are then the
// key's centre, where a miss evaluates the cut, or else the hit's own inputs. One function
// for the megakernel's evaluateMaterialThroughCut and the wavefront's cut passes.
bool cacheReadCut(uvec4 info, uvec4 cut, uvec2 object, MaterialInputs inputs, inout bool keyed,
                  out CacheKey key, out MaterialInputs keyInputs,
                  out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  keyed = keyed && cacheCutKeyFor(info, cut, object, inputs, key, keyInputs);
  if (!keyed) {
    keyInputs = inputs;
    return false;
  }
  g_cacheLookups += 1u;
  if (cacheRead(key, values)) {
    g_cacheHits += 1u;
    return true;
  }
  g_cacheMisses += 1u;
  g_cacheMissed = true;
  return false;
}

// A material keyed by its cut (thesis §7): the cache holds the cut's values under the key
// cacheCutKeyFor gives, and the rest of the graph always runs with this hit's inputs. A miss
// evaluates the cut at the key's centre with the key's footprint, always (not only with
// --snap-uv), so a cached value is a function of the key. With MG_CACHE_FILTER the rest runs
// with the filter's blend (or pick) of such entries. `object` is (instance, mesh) of the hit.
// Where the hit takes no key (`keyed` false: the cache is off for this frame or bounce) or
// has no usable one (non-finite coordinates, a voxel outside the fixed-point range), the cut
// runs at the hit's own inputs: the rest of the cut's values is the whole graph's result, so
// the pass holds one copy of the graph (cut and rest), not a second whole graph for that case,
// which the GPU's compiler would inline beside it.
void evaluateMaterialThroughCut(uint materialId, uvec4 cut, uvec2 object, MaterialInputs inputs,
                                bool keyed, out MaterialOutputs outputs) {
  uvec4 info = cacheInfoOf(materialId);
  float values[MG_CACHE_VALUES];
  bool usable = keyed && frame.cache.x != 0u;
#ifdef MG_CACHE_FILTER
  CacheFilterSite site;
  if (!usable) {
  } else if (cut.x == kCacheCutUv) {
    usable = cacheUvFilterSite(inputs, site);
  } else if (cut.x == kCacheCutWorld) {
    usable = cacheVoxelFilterSite(inputs.position.v, inputs.position.x, inputs.position.y, site);
  }
#ifndef MG_OMIT_OBJECT_INPUTS
  else if (cut.x == kCacheCutObject) {
    usable = cacheVoxelFilterSite(inputs.objectPosition.v, inputs.objectPosition.x,
                                  inputs.objectPosition.y, site);
  }
#endif
  else {
    usable = false;
  }
  if (usable) {
    cacheFilteredValues(materialId, info, cut.x, cutObjectWord(cut, object), object, inputs,
                        site, values);
  } else {
    evaluateMaterialCutSwitch(materialId, inputs, values);
  }
#else
  CacheKey key;
  MaterialInputs keyInputs;
  if (!cacheReadCut(info, cut, object, inputs, usable, key, keyInputs, values)) {
    evaluateMaterialCutSwitch(materialId, keyInputs, values);
    if (usable) cacheWrite(key, values);
  }
#endif  // MG_CACHE_FILTER
  evaluateMaterialRestSwitch(materialId, inputs, values, outputs);
}
#endif  // MG_CACHE_CUTS

void evaluateMaterialCached(uint materialId, uvec2 object, MaterialInputs inputs,
                            out MaterialOutputs outputs) {
#ifdef MG_CACHE_CUTS
  uvec4 cut = cutInfoOf(materialId);
  // (A wavefront pass of a graph without a cut never takes this branch: nothing compiled.)
#if defined(MG_WAVEFRONT) && !defined(MG_CACHE_CUT_PASS)
  cut.x = kCacheCutNone;
#endif
  if (cut.x != kCacheCutNone) {
    evaluateMaterialThroughCut(materialId, cut, object, inputs, true, outputs);
    return;
  }
#endif
  uvec4 info = cacheInfoOf(materialId);
#ifdef MG_CACHE_FILTER
  // A whole uv-only material, filtered: its packed outputs blended (or one entry's picked),
  // then unpacked as a hit's values are.
  CacheFilterSite site;
  if (info.x == 0u || frame.cache.x == 0u || !cacheUvFilterSite(inputs, site)) {
    evaluateMaterialDirect(materialId, inputs, outputs);
    return;
  }
  float blended[MG_CACHE_VALUES];
  cacheFilteredValues(materialId, info, kCacheCutNone, 0u, object, inputs, site, blended);
  outputs = cacheUnpack(info.x, blended, inputs);
#else
  CacheKey key;
  if (info.x == 0u || frame.cache.x == 0u || !cacheKeyFor(info, inputs, key)) {
    evaluateMaterialDirect(materialId, inputs, outputs);
    return;
  }
  g_cacheLookups += 1u;
  float values[MG_CACHE_VALUES];
  if (cacheRead(key, values)) {
    g_cacheHits += 1u;
    outputs = cacheUnpack(info.x, values, inputs);
    return;
  }
  g_cacheMisses += 1u;
  g_cacheMissed = true;
#ifdef MG_CACHE_SNAP_UV
  evaluateMaterialDirect(materialId, texelInputs(inputs, key.texelUv, key.texelSize), outputs);
#else
  evaluateMaterialDirect(materialId, inputs, outputs);
#endif
  cachePack(info.x, outputs, values);
  cacheWrite(key, values);
#endif  // MG_CACHE_FILTER
}

#endif  // !MG_WAVEFRONT || (MG_WAVEFRONT_MATERIAL && MG_CACHE_TEXEL)

#endif
