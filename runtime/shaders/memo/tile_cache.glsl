// The tile cache of thesis §4.6 and §5.4: each hash-table entry holds a tile of
// MG_TILE_W x MG_TILE_H texels of a material's outputs, keyed by (material, mip level, tile);
// missing tiles are computed by the whole subgroup together, one texel per lane (§5.4.3).
// Included by path_tracer.glsl when the host defines MG_CACHE_TILE, with everything
// texel_cache.glsl takes (values, probe, eviction, update counter) and
//   MG_TILE_W, MG_TILE_H   texels stored per tile (W * H <= the subgroup size),
//   MG_TILE_BILINEAR       (optional) bilinear filtering; tiles then overlap by one texel,
//                          covering (W-1) x (H-1) texel spacings (eq. 5.12-5.15),
//   MG_TILE_STORAGE        kTileStorage{Entry, Buffer, Texture2D, Texture3D} (§5.4.1),
//   MG_TILE_IMAGE_FORMAT   the storage image's format qualifier (rgba32f or rgba16f),
//   MG_TILE_GROUP_BY_MATERIAL (optional) §5.4.4's order of missing tiles,
//   MG_TILE_FILL_DEFERRED  (optional) missing tiles are queued and computed by a second
//                          pass (MG_TILE_FILL_PASS: tileFillTexel), not by the subgroup;
//                          MG_TILE_QUEUE_CAPACITY tiles a frame at most,
//   MG_CACHE_ENTRY_WORDS   the texel words stored in an entry (0 unless kTileStorageEntry).
// With the subgroup fill every lane of the subgroup must call evaluateMaterialTiled
// together (path_tracer.glsl keeps its loops uniform for that): the texels of a tile are
// assigned to lanes by rank, and the lane that stores a tile's last texel publishes it
// (tileCountTexels: a release fence and an atomic count per texel, never a subgroup
// operation, orders the texels before the key). The deferred fill has no such need.
#ifndef MG_TILE_CACHE_GLSL
#define MG_TILE_CACHE_GLSL
#ifndef MG_TILE_FILL_DEFERRED
// The subgroup computation of §5.4.3; the deferred fill needs no subgroup operation.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#endif

#include "texel_cache.glsl"

const uint kTileW = uint(MG_TILE_W);
const uint kTileH = uint(MG_TILE_H);
const uint kTileTexels = kTileW * kTileH;
#ifdef MG_TILE_BILINEAR
// Eq. 5.12-5.15 with bilinear filtering: s is one less than the texels stored, and the
// texels sit on the corners of the texel grid.
const vec2 kTileArea = vec2(float(kTileW - 1u), float(kTileH - 1u));
const vec2 kTexelOffset = vec2(0.0);
const uint kTileTaps = 4u;
#else
const vec2 kTileArea = vec2(float(kTileW), float(kTileH));
const vec2 kTexelOffset = vec2(0.5);  // nearest: a texel's value is its centre's
const uint kTileTaps = 1u;
#endif
const uint kNoLane = 0xFFFFFFFFu;
// Tiles computed together in one iteration at most (a 32-lane subgroup with 1x1 tiles).
const uint kMaxTileSlots = 32u;

// Counts of this invocation, added to gpu::Counters once per pixel.
uint g_tilesComputed = 0u;
uint g_duplicateTiles = 0u;
uint g_tileFallbacks = 0u;
uint g_tileRepacks = 0u;
// A number unique to this invocation (its pixel), to detect a subgroup repack (below).
uint g_invocationId = 0u;
// Tiles this invocation published (its texel was a tile's last; path_tracer.glsl adds them
// to Counters::cacheTilesPublished) and locked tiles it gave back empty after a repack
// (counted by cache_selftest's tile fill check only).
uint g_tilesPublished = 0u;
uint g_tilesGivenUp = 0u;
#ifdef MG_TILE_TEST_REPACKS
// Test hook (below): the first pass of an iteration at which the subgroup looks repacked.
// 0 in the renderer: every computation is given up before anything is stored.
uint g_testRepackPass = 0u;
#endif

// ---- Texel storage (§5.4.1) --------------------------------------------------------------

#if MG_TILE_STORAGE == 0
// In the entry, after its header: texel t at t * kCacheValueWords (fp32 or fp16 words).
void tileStoreTexel(uint entry, uint texel, float values[MG_CACHE_VALUES]) {
  cacheStoreValues(cacheEntryOffset(entry) + kCacheHeader + texel * kCacheValueWords, values);
}
void tileLoadTexel(uint entry, uint texel, out float values[MG_CACHE_VALUES]) {
  cacheLoadValues(cacheEntryOffset(entry) + kCacheHeader + texel * kCacheValueWords, values);
}
#elif MG_TILE_STORAGE == 1
// A separate buffer, entry-major, the same words as in the entry.
layout(set = 0, binding = kBindingTileTexels, std430) MG_CACHE_COHERENT buffer TileTexelBlock {
  uint tileTexels[];
};
uint tileTexelWord(uint entry, uint texel) { return (entry * kTileTexels + texel) * kCacheValueWords; }
// Relaxed atomics of device scope, as the values in the cache buffer (cacheStoreWord): a read
// may race with a writer that locked the entry meanwhile, and its check discards what it read.
void tileStoreTexel(uint entry, uint texel, float values[MG_CACHE_VALUES]) {
  uint word = tileTexelWord(entry, texel);
  for (uint w = 0u; w < kCacheValueWords; ++w)
    atomicStore(tileTexels[word + w], cacheValueWord(values, w), gl_ScopeDevice,
                gl_StorageSemanticsBuffer, gl_SemanticsRelaxed);
}
void tileLoadTexel(uint entry, uint texel, out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  uint word = tileTexelWord(entry, texel);
  for (uint w = 0u; w < kCacheValueWords; ++w) {
#ifdef MG_CACHE_QUIESCENT_READS
    uint stored = tileTexels[word + w];  // nothing stores a texel in this dispatch
#else
    uint stored = atomicLoad(tileTexels[word + w], gl_ScopeDevice, gl_StorageSemanticsBuffer,
                             gl_SemanticsRelaxed);
#endif
    cacheValueFromWord(stored, w, values);
  }
}
#else
// Images hold four values per texel; a texel's value groups sit side by side in x (2D) or
// stacked in z (3D). Tiles are laid out row by row, frame.cache.w tiles per row.
const uint kValueGroups = (uint(MG_CACHE_VALUES) + 3u) / 4u;
#if MG_TILE_STORAGE == 2
layout(set = 0, binding = kBindingTileImage, MG_TILE_IMAGE_FORMAT) MG_CACHE_COHERENT uniform image2D tileImage;
ivec2 tileTexelAt(uint entry, uint texel, uint group) {
  uint tilesPerRow = frame.cache.w;
  uint x = (entry % tilesPerRow) * kTileW * kValueGroups + group * kTileW + texel % kTileW;
  uint y = (entry / tilesPerRow) * kTileH + texel / kTileW;
  return ivec2(x, y);
}
#else
layout(set = 0, binding = kBindingTileImage, MG_TILE_IMAGE_FORMAT) MG_CACHE_COHERENT uniform image3D tileImage;
ivec3 tileTexelAt(uint entry, uint texel, uint group) {
  uint tilesPerRow = frame.cache.w;
  uint x = (entry % tilesPerRow) * kTileW + texel % kTileW;
  uint y = (entry / tilesPerRow) * kTileH + texel / kTileW;
  return ivec3(x, y, group);
}
#endif
void tileStoreTexel(uint entry, uint texel, float values[MG_CACHE_VALUES]) {
  for (uint g = 0u; g < kValueGroups; ++g) {
    vec4 group = vec4(0.0);
    for (uint c = 0u; c < 4u; ++c)
      if (4u * g + c < uint(MG_CACHE_VALUES)) group[c] = values[4u * g + c];
#ifdef MG_CACHE_VALUE_FP16
    // An rgba16f store of a value past 65504 gives infinity (a bright emission would poison
    // every path that reads the texel): clamp as the buffer's fp16 words do.
    group = clamp(group, vec4(-kCacheHalfMax), vec4(kCacheHalfMax));
#endif
    imageStore(tileImage, tileTexelAt(entry, texel, g), group);
  }
}
void tileLoadTexel(uint entry, uint texel, out float values[MG_CACHE_VALUES]) {
  for (uint g = 0u; g < kValueGroups; ++g) {
    vec4 group = imageLoad(tileImage, tileTexelAt(entry, texel, g));
    for (uint c = 0u; c < 4u; ++c)
      if (4u * g + c < uint(MG_CACHE_VALUES)) values[4u * g + c] = group[c];
  }
}
#endif

// The texel stores (buffer or image) before what publishes them (the release fence before
// a texel's count, tileCountTexels): cacheFence (texel_cache.glsl) orders image and buffer
// memory together.
void tileStorageBarrier() {
  cacheFence();
}

// Adds this invocation's tile counts to gpu::Counters. The subgroup computation of tiles needs
// subgroup operations, so its sums have them (every invocation of the subgroup must call
// it); the deferred fill runs without (lavapipe's raygen has none).
void tileAddCounts() {
#if defined(MG_SUBGROUP_RAY_COUNT) || !defined(MG_TILE_FILL_DEFERRED)
  uvec4 tileCounts =
      subgroupAdd(uvec4(g_tilesComputed, g_duplicateTiles, g_tileFallbacks, g_tileRepacks));
  if (subgroupElect() && any(notEqual(tileCounts, uvec4(0u)))) {
#else
  uvec4 tileCounts = uvec4(g_tilesComputed, g_duplicateTiles, g_tileFallbacks, g_tileRepacks);
  if (any(notEqual(tileCounts, uvec4(0u)))) {
#endif
    atomicAdd(counters.cacheTilesComputed, tileCounts.x);
    atomicAdd(counters.cacheDuplicateTiles, tileCounts.y);
    atomicAdd(counters.cacheTileFallbacks, tileCounts.z);
    atomicAdd(counters.cacheTileRepacks, tileCounts.w);
  }
}

// ---- Keys and filtering (§5.4.2) ---------------------------------------------------------

// A lookup's tile: its key, mip level, position in multiples of the tile size (eq.
// 5.12-5.13) and the hit's position inside it in texel units, [0, s) (eq. 5.14-5.15 times s).
struct TileRequest {
  CacheKey key;
  int level;
  vec2 tile;
  vec2 local;
};

bool tileRequestFor(uvec4 info, MaterialInputs inputs, out TileRequest request) {
  bool usable = cacheMipLevel(inputs, request.level);
  vec2 scaled = exp2(float(request.level)) * inputs.uv.v / kTileArea;
  request.tile = floor(scaled);
  request.local = clamp((scaled - request.tile) * kTileArea, vec2(0.0), kTileArea);
  request.key = cacheKeyOf(info, request.level, request.tile);
  return usable;
}

// The texels a lookup at `local` reads and their weights: one for nearest, four bilinear.
void tileTaps(vec2 local, out uint texels[4], out vec4 weights) {
#ifdef MG_TILE_BILINEAR
  uvec2 i0 = uvec2(min(floor(local), kTileArea - 1.0));
  vec2 f = clamp(local - vec2(i0), 0.0, 1.0);
  texels[0] = i0.y * kTileW + i0.x;
  texels[1] = texels[0] + 1u;
  texels[2] = texels[0] + kTileW;
  texels[3] = texels[2] + 1u;
  weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
#else
  uvec2 i = uvec2(min(floor(local), kTileArea - 1.0));
  texels[0] = i.y * kTileW + i.x;
  texels[1] = texels[0];
  texels[2] = texels[0];
  texels[3] = texels[0];
  weights = vec4(1.0, 0.0, 0.0, 0.0);
#endif
}

// §5.3.3-5.3.4 for a tile: find the key, then read the texels the lookup needs between the
// two key checks and filter them.
bool tileRead(TileRequest request, out float values[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  int entry = cacheFind(request.key);
  if (entry < 0) return false;
  uint texels[4];
  vec4 weights;
  tileTaps(request.local, texels, weights);
  uint counterBefore = cacheReadBegin(uint(entry), request.key);
#ifdef MG_TILE_BILINEAR
  [[unroll]] for (uint tap = 0u; tap < 4u; ++tap) {
    float texel[MG_CACHE_VALUES];
    tileLoadTexel(uint(entry), texels[tap], texel);
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] += weights[tap] * texel[i];
  }
#else
  tileLoadTexel(uint(entry), texels[0], values);
#endif
  return cacheReadValid(uint(entry), request.key, counterBefore);
}

// §6.7.2: records a computed tile in this frame's set; true when it was there already (a
// duplicate computed by another subgroup). A full probe range counts nothing.
layout(set = 0, binding = kBindingTileLog, std430) buffer TileLogBlock {
  uint tileLog[];
};
bool tileLogDuplicate(CacheKey key) {
  uint base = cachePcg(key.base ^ cachePcg(key.hash));
  [[unroll]] for (uint d = 0u; d < kTileLogProbe; ++d) {
    uint slot = (base + d) & (kTileLogEntries - 1u);
    uint previous = atomicCompSwap(tileLog[slot], 0u, key.hash);
    if (previous == 0u) return false;
    if (previous == key.hash) return true;
  }
  return false;
}

// `inputs` at texel `texel` of the tile at `tile` (in multiples of the tile size) of mip
// level `level`: its uv (a texel of level m is 2^-m wide; nearest: its centre, bilinear: its
// corner) with one texel's footprint (texelInputs, eq. 5.16-5.17).
MaterialInputs tileTexelInputs(MaterialInputs inputs, int level, vec2 tile, uint texel) {
  float texelSize = exp2(-float(level));
  vec2 texelIndex = vec2(float(texel % kTileW), float(texel / kTileW));
  return texelInputs(inputs, (tile * kTileArea + texelIndex + kTexelOffset) * texelSize,
                     texelSize);
}

#ifdef MG_TILE_FILL_DEFERRED
// ---- Deferred computation of missing tiles ------------------------------------------------
// The subgroup computation below needs every lane back in place after the material's
// evaluation, which a callable does not promise (NVIDIA's raygen regroups lanes, and the
// tile is then given up). Deferred, a request only queues its tile; a second pass after
// the frame's trace computes each queued tile with one invocation per texel and no lane
// exchanging anything, and publishes it for the next frame.

layout(set = 0, binding = kBindingTileQueue, std430) coherent buffer TileQueueBlock {
  TileQueueHeader tileQueueHeader;
  TileFillItem tileQueue[];
};
const uint kTileQueueCapacity = uint(MG_TILE_QUEUE_CAPACITY);

// Queues the tile of a missed lookup once per frame: the first request (the tile log is
// this frame's set of queued tiles) locks an entry and writes the queue item; a full queue
// gives the entry back. The requester evaluates its own hit either way.
void tileEnqueue(uint materialId, TileRequest tile) {
  if (tileLogDuplicate(tile.key)) return;
  uint evicted;
  int entry = cacheLockEvicting(tile.key, evicted);
  if (entry < 0) return;
  uint slot = atomicAdd(tileQueueHeader.count, 1u);
  if (slot >= kTileQueueCapacity) {
    cacheRestore(uint(entry), evicted);  // nothing stored: the entry's tile, if any, back
    g_tileFallbacks += 1u;
    return;
  }
  g_tilesComputed += 1u;
  tileQueue[slot].entry = uint(entry);
  tileQueue[slot].keyBase = tile.key.base;
  tileQueue[slot].keyHash = tile.key.hash;
  tileQueue[slot].materialId = materialId;
  tileQueue[slot].level = uint(tile.level);
  tileQueue[slot].tileX = floatBitsToUint(tile.tile.x);
  tileQueue[slot].tileY = floatBitsToUint(tile.tile.y);
  tileQueue[slot].texelsDone = 0u;
}

// The inputs of texel `texel` of a queued tile. Cacheable materials read nothing but uv
// (§4.2), so the other inputs are placeholders; textureBase is the caller's (the switch's
// case sets it, a wavefront material pass has its own).
MaterialInputs tileFillInputs(TileFillItem item, uint texel) {
  MaterialInputs inputs;
  inputs.position.v = vec3(0.0);
  inputs.position.x = vec3(0.0);
  inputs.position.y = vec3(0.0);
  inputs.normal = vec3(0.0, 0.0, 1.0);
  inputs.tangent = vec3(1.0, 0.0, 0.0);
  inputs.bitangentSign = vec3(1.0, 0.0, 0.0);
  inputs.vertexColor = vec4(1.0);
  inputs.view = vec3(0.0, 0.0, 1.0);
  inputs.time = frame.cameraForward.w;
  inputs.textureBase = 0;
#ifndef MG_OMIT_OBJECT_INPUTS
  inputs.generated = inputs.position;
  inputs.generatedScale = vec3(1.0);
  inputs.objectPosition = inputs.position;
  inputs.geometricNormal = vec3(0.0, 0.0, 1.0);
  inputs.objectNormal = inputs.normal;
  inputs.objectLocation = vec3(0.0);
  inputs.objectRandom = 0.0;
  inputs.backfacing = 0.0;
#endif
#ifndef MG_OMIT_PATH_INPUTS
  inputs.rayFlags = MG_RAY_CAMERA;
  inputs.rayLength = 0.0;
  inputs.rayDepth = 0;
  inputs.diffuseDepth = 0;
  inputs.glossyDepth = 0;
  inputs.transmissionDepth = 0;
  inputs.closureSeed = 0u;
#endif
#ifndef MG_OMIT_TRACED_INPUTS
  inputs.ambientOcclusion = 1.0;  // never read: a graph with a traced input is not cacheable
  inputs.bevelNormal = inputs.normal;
#endif
  vec2 tile = vec2(uintBitsToFloat(item.tileX), uintBitsToFloat(item.tileY));
  return tileTexelInputs(inputs, int(item.level), tile, texel);
}

// Stores the computed texel `texel` of queue slot `slot`; the last of the tile's texels to be
// stored publishes the entry (its key unlocks it).
void tileFillStore(uint slot, TileFillItem item, uint texel, MaterialOutputs outputs) {
  float values[MG_CACHE_VALUES];
  cachePack(mg_materialCacheInfo[item.materialId].x, outputs, values);
  tileStoreTexel(item.entry, texel, values);
  tileStorageBarrier();
  if (atomicAdd(tileQueue[slot].texelsDone, 1u) == kTileTexels - 1u) {
    // Every texel of the tile was stored (and made visible) before its count went up.
    cacheFence();
    CacheKey key;
    key.base = item.keyBase;
    key.hash = item.keyHash;
    key.texelUv = vec2(0.0);
    cacheUnlock(item.entry, key);
    atomicAdd(counters.cacheTilesPublished, 1u);
  }
}

#ifdef MG_TILE_FILL_PASS
// The fill pass: invocation i computes texel i % (W*H) of queue slot i / (W*H).
void tileFillTexel(uint invocation) {
  uint slot = invocation / kTileTexels;
  uint texel = invocation % kTileTexels;
  if (slot >= min(tileQueueHeader.count, kTileQueueCapacity)) return;
  TileFillItem item = tileQueue[slot];
  MaterialOutputs outputs;
  evaluateMaterialDirect(item.materialId, tileFillInputs(item, texel), outputs);
  tileFillStore(slot, item, texel, outputs);
}
#endif
#else

// ---- Cooperative computation of missing tiles (§5.4.3) -----------------------------------

// A computed texel as the storage will give it back (fp16: clamped to ±65504 and rounded to
// a half), so the lanes served by the exchange shade with what later hits read.
void tileQuantize(inout float values[MG_CACHE_VALUES]) {
#ifdef MG_CACHE_VALUE_FP16
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i)
    values[i] = unpackHalf2x16(packHalf2x16(vec2(clamp(values[i], -kCacheHalfMax, kCacheHalfMax), 0.0))).x;
#endif
}

// Step 7, publishing a tile whose texels other lanes stored. A subgroup operation carries
// data but does not synchronize memory (the Vulkan memory model has no happens-before
// through a ballot or shuffle), so a fence in each lane followed by a ballot and the
// locking lane's key store ordered nothing across lanes: a reader that saw the key could
// read stale texels on a GPU. Instead each lane that stores a texel then does a release
// fence (cacheFence: buffer and image memory, so every --tile-storage) and an atomic add
// on the entry's count word (kCacheTileCount), as the deferred fill does on its queue item.
// The adds of one lock form a release sequence on that word (every write to it is an atomic
// read-modify-write), so the add that completes the count reads a value that every earlier
// add's release sequence contains; with the acquire fence after it, each earlier lane's
// fence synchronizes with it (fence synchronization), and every texel store happens-before
// that lane's key store, which cacheUnlock orders after a release fence in turn. The
// completing lane, whichever it is, publishes: a tile has exactly one.
// The word: the clock cannot count (lru's read touches store it with a plain store even
// while the entry is locked: a reader checks the key, a lock comes, the reader stamps), nor
// can the update counter (optional; cacheLock bumps it after the lock's exchange, with no
// order against this tile's lanes). The count word is touched only by the lanes of the tile
// that holds the lock, and it is 0 whenever the entry is unlocked: the completing lane
// resets it before the key's release. A later lock's lanes add to it only after that lock's
// exchange read the key (their entry index comes from it through a shuffle), the same
// dependency by which their texel stores follow the lock.
// The low bits count texels (W*H <= the subgroup size <= 128); a tile given up (a repack,
// below) adds its missing texels plus kTileCountCancel, so the count still completes exactly
// once, and the completing add, the locking lane's or a late texel's, empties the entry.
const uint kTileCountMask = 0xFFFFu;
const uint kTileCountCancel = 0x10000u;

// Adds `amount` to the count of the tile locked in `entry` (after a release fence: the
// caller's texel store, or nothing to order for a give-up); the add that completes it
// publishes the tile under `key`, or gives the entry back empty when the tile was given up.
void tileCountTexels(uint entry, CacheKey key, uint amount) {
  uint word = cacheEntryOffset(entry) + kCacheTileCount;
  uint after = cacheAddWord(word, amount) + amount;
  if ((after & kTileCountMask) != kTileTexels) return;
  // Acquire: every lane's texel (stored before its release fence and its add) happens-before
  // what follows, here the key store.
  cacheFence();
  cacheExchangeWord(word, 0u);  // 0 for the entry's next lock, before the key
  if ((after & kTileCountCancel) != 0u) {
    cacheFence();  // the reset before the key that lets the next lock in
    cacheUnlockEmpty(entry);
    g_tilesGivenUp += 1u;
    return;
  }
  cacheUnlock(entry, key);  // clock, release fence, key
  g_tilesPublished += 1u;
  // §6.7.2's duplicates: a tile published twice in a frame, logged by the lane that
  // publishes, once per tile. Logged when published, not when locked: a tile given up after
  // a callable repack (its entry emptied, counted as a repack) and then computed by another
  // subgroup is one computation, not two; logged at the lock, those retries were most of
  // the 77-85 % "duplicates" once counted on a held-out classroom path.
  if (tileLogDuplicate(key)) g_duplicateTiles += 1u;
}

// A repack gave the computation up before pass `pass`: the locking lane of the tile with
// place `placeInPasses` among the locked tiles (its texels are numbers placeInPasses * W*H ..)
// hands the entry back. Texels numbered below pass * activeCount were stored and counted in
// the earlier, stable passes; the rest never will be.
void tileGiveUp(uint entry, CacheKey key, uint evicted, uint placeInPasses, uint pass,
                uint activeCount) {
  uint first = placeInPasses * kTileTexels;
  uint done = pass * activeCount;
  uint stored = done > first ? min(done - first, kTileTexels) : 0u;
  // Complete in an earlier pass: its last lane published it, and it must stay published.
  if (stored == kTileTexels) return;
  if (stored == 0u) {
    // Nothing stored or counted under this lock: nobody else will touch the entry, which
    // still holds the tile it held before (if any) and gets it back (cacheRestore).
    cacheRestore(entry, evicted);
    g_tilesGivenUp += 1u;
    return;
  }
  // Partly stored: the count completes with the missing texels and the cancel mark, here or
  // in the add of a lane whose texel add is still on its way; that one empties the entry.
  tileCountTexels(entry, key, kTileCountCancel + kTileTexels - stored);
}

// Shuffles a value array from lane `source` (every lane takes part, each with its source).
void tileShuffleValues(float values[MG_CACHE_VALUES], uint source,
                       out float result[MG_CACHE_VALUES]) {
  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) result[i] = subgroupShuffle(values[i], source);
}

// §5.4.4: the order in which missing tiles are selected. Materials with an even number of
// requesting lanes come first so tiles of one material pair up in an iteration; the
// thesis's offset is the high bit here. Without grouping, lanes go in ascending order.
uint tileSortKey(bool pending, uint materialId) {
#ifdef MG_TILE_GROUP_BY_MATERIAL
  uint sortKey = 0xFFFFFFFFu;
  bool unresolved = pending;
  while (subgroupAny(unresolved)) {
    uint first = subgroupBallotFindLSB(subgroupBallot(unresolved));
    uint material = subgroupShuffle(materialId, first);
    bool same = unresolved && materialId == material;
    uint count = subgroupBallotBitCount(subgroupBallot(same));
    if (same) {
      sortKey = (materialId & 0x7FFFFFFFu) | ((count & 1u) != 0u ? 0x80000000u : 0u);
      unresolved = false;
    }
  }
  return sortKey;
#else
  return 0u;
#endif
}

// The lane of the `rank`-th set bit of the ballot `lanes`, counting from lane 0; the calling
// lane itself when `lanes` has no more than `rank` bits set.
uint laneOfRank(uvec4 lanes, uint rank) {
  for (uint c = 0u; c < 4u; ++c) {
    uint bits = lanes[c];
    uint count = uint(bitCount(bits));
    if (rank < count) {
      for (uint k = 0u; k < rank; ++k) bits &= bits - 1u;  // drop the lowest set bits
      return 32u * c + uint(findLSB(bits));
    }
    rank -= count;
  }
  return gl_SubgroupInvocationID;
}

// Steps 1-8 of §5.4.3, repeated until no lane of the subgroup requests a tile. `request`:
// this lane missed the cache for `tile` of `materialId`; on return `served` says whether
// `values` now holds its filtered texel(s), computed by the subgroup.
// Texels go to the active lanes by rank, not by lane index: a driver need not reconverge
// every lane here (on NVIDIA a raygen subgroup is often partial after a divergent trace or
// callable), and a shuffle may only read active lanes. When fewer lanes than a tile's
// texels are active, the tile is computed in several passes.
void tileComputeMissing(bool request, uint materialId, uvec4 info, TileRequest tile,
                        MaterialInputs inputs, inout float values[MG_CACHE_VALUES],
                        out bool served) {
  served = false;
  uint lane = gl_SubgroupInvocationID;
  uvec4 activeLanes = subgroupBallot(true);
  uint activeCount = subgroupBallotBitCount(activeLanes);
  uint rank = subgroupBallotExclusiveBitCount(activeLanes);
  const uint tilesPerIteration = clamp(activeCount / kTileTexels, 1u, kMaxTileSlots);
  bool pending = request;
  uint sortKey = tileSortKey(pending, materialId);
  uint taps[4];
  vec4 weights;
  tileTaps(tile.local, taps, weights);
  while (subgroupAny(pending)) {
    // Steps 1-2: select up to tilesPerIteration tiles, lowest requesting lane first (or
    // §5.4.4's order); the selected lane broadcasts its tile and every lane asking for the
    // same tile is served by this slot.
    uint slotLeader[kMaxTileSlots];
    uint mySlot = kNoLane;
    uint selected = 0u;
    for (uint slot = 0u; slot < tilesPerIteration; ++slot) {
      uvec4 candidates = subgroupBallot(pending);
      if (subgroupBallotBitCount(candidates) == 0u) break;
#ifdef MG_TILE_GROUP_BY_MATERIAL
      uint nextKey = subgroupMin(pending ? sortKey : 0xFFFFFFFFu);
      candidates = subgroupBallot(pending && sortKey == nextKey);
#endif
      uint leader = subgroupBallotFindLSB(candidates);
      // A slot is a cache key (graph, level, tile: eq. 5.8-5.10), not a material id:
      // materials that share a graph share the key, so they share the slot too (matched by
      // material id, the same tile was computed once per material and counted a duplicate).
      uint leaderBase = subgroupShuffle(tile.key.base, leader);
      uint leaderHash = subgroupShuffle(tile.key.hash, leader);
      if (pending && tile.key.base == leaderBase && tile.key.hash == leaderHash) {
        pending = false;
        mySlot = slot;
      }
      slotLeader[slot] = leader;
      selected += 1u;
    }

    // Step 5 first: the lane of rank s locks an entry for slot s (before any texel is
    // written, so its texels can be stored as they are computed, pass by pass).
    uint lockSource = rank < selected ? slotLeader[rank] : lane;
    CacheKey lockKey;
    lockKey.base = subgroupShuffle(tile.key.base, lockSource);
    lockKey.hash = subgroupShuffle(tile.key.hash, lockSource);
    lockKey.texelUv = vec2(0.0);
    // The locking lane also holds the rest of its slot's request, for the workers to read.
    uint slotMaterial = subgroupShuffle(materialId, lockSource);
    uvec4 slotInfo = subgroupShuffle(info, lockSource);
    int slotLevel = subgroupShuffle(tile.level, lockSource);
    vec2 slotTile = subgroupShuffle(tile.tile, lockSource);
#ifdef MG_TILE_TEST_REPACKS
#ifdef MG_TILE_TEST_REPACK_PERCENT
    // Test hook (below) in MG_TILE_TEST_REPACK_PERCENT % of the iterations only: a hash of the
    // subgroup (its first invocation), its first slot's tile and the frame, the same in every
    // lane (the H200 gives up about 60 % of the tiles it starts on the classroom).
    bool testRepackHere =
        cachePcg(subgroupBroadcastFirst(g_invocationId) ^
                 cachePcg(subgroupBroadcastFirst(lockKey.hash) ^ cachePcg(frame.cache.y))) %
            100u <
        uint(MG_TILE_TEST_REPACK_PERCENT);
#else
    const bool testRepackHere = true;
#endif
#endif
    int entry = -1;
    uint evicted = kCacheKeyEmpty;  // the key the locked entry held: a give-up restores it
    if (rank < selected) entry = cacheLockEvicting(lockKey, evicted);
    // Only tiles with a locked entry are computed. A slot the policy declined (none, with
    // its probe range full) or another subgroup holds locked could not be stored: its
    // W x H evaluations would serve only this subgroup's requesters, who evaluate their own
    // hits instead, one evaluation each, as a texel-cache miss does (the thesis computes
    // such tiles anyway; with no eviction and a full cache that made every tile miss cost
    // a whole tile).
    uvec4 lockedLanes = subgroupBallot(entry >= 0);
    uint lockedCount = subgroupBallotBitCount(lockedLanes);
    // A served lane's slot was locked by the lane of rank mySlot; that lane's rank among the
    // locking lanes is the slot's place among the computed tiles.
    uint mySlotLane = mySlot != kNoLane ? laneOfRank(activeLanes, mySlot) : lane;
    bool mine = mySlot != kNoLane && subgroupBallotBitExtract(lockedLanes, mySlotLane);
    uint lockedPlace = subgroupBallotExclusiveBitCount(lockedLanes);  // a locking lane's tile
    uint myComputed = subgroupShuffle(lockedPlace, mySlotLane);

    // Steps 2-4 and 6, pass by pass: the lane of rank r computes texel p * activeCount + r
    // of the locked tiles (texel t of the c-th locked slot is number c * W * H + t), with
    // the fictional derivatives of eq. 5.16-5.17 (a texel of level m is 2^-m wide), and
    // stores it. Step 8 inside each pass: lanes served by this iteration take the texels
    // they filter from the lanes that computed them.
    const uint total = lockedCount * kTileTexels;
    const uint passes = (total + activeCount - 1u) / activeCount;
    float filtered[MG_CACHE_VALUES];
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) filtered[i] = 0.0;
    for (uint pass = 0u; pass < passes; ++pass) {
      uint number = pass * activeCount + rank;
      bool worker = number < total;
      // The lane that locked this texel's tile (for lanes without work, any active lane:
      // laneOfRank past the last rank gives the lane itself).
      uint slotLane = laneOfRank(lockedLanes, number / kTileTexels);
      uint texel = number % kTileTexels;
      uint workMaterial = subgroupShuffle(slotMaterial, slotLane);
      uvec4 workInfo = subgroupShuffle(slotInfo, slotLane);
      int workLevel = subgroupShuffle(slotLevel, slotLane);
      vec2 workTile = subgroupShuffle(slotTile, slotLane);
      int tileEntry = subgroupShuffle(entry, slotLane);
      // The tile's key, for the lane whose texel completes it: that lane publishes it.
      CacheKey tileKey;
      tileKey.base = subgroupShuffle(lockKey.base, slotLane);
      tileKey.hash = subgroupShuffle(lockKey.hash, slotLane);
      tileKey.texelUv = vec2(0.0);
      tileKey.texelSize = 0.0;
      float texelValues[MG_CACHE_VALUES];
      for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) texelValues[i] = 0.0;
#if defined(MG_MATERIAL_CALLABLES) || defined(MG_TILE_TEST_REPACKS)
      // Who this subgroup is before the evaluation: its first lane's invocation.
      uint firstBefore = subgroupBroadcastFirst(g_invocationId);
#endif
      if (worker) {
        // Counted where it happens: the lane that evaluates a tile's first texel.
        if (texel == 0u) g_tilesComputed += 1u;
        MaterialOutputs texelOutputs;
        evaluateMaterialDirect(workMaterial, tileTexelInputs(inputs, workLevel, workTile, texel),
                               texelOutputs);
        cachePack(workInfo.x, texelOutputs, texelValues);
        tileQuantize(texelValues);
      }
#if defined(MG_MATERIAL_CALLABLES) || defined(MG_TILE_TEST_REPACKS)
      // executeCallableEXT may repack invocations into other subgroups (SPIR-V "invocation
      // repack instruction"); the exchange needs the same invocations in the same lanes as
      // before: every lane at its old index, all from the same subgroup (the same first
      // invocation before the call), the same lanes active. If not, nothing more is stored,
      // the locked tiles not yet complete go back to empty (tileGiveUp: a tile completed in an
      // earlier pass stays published), and every requester evaluates its own hit (both
      // counted).
#ifdef MG_TILE_TEST_REPACKS
      // Test hook: as if the upper half of the lanes came back from the call out of another
      // subgroup, at the same lane indices and with the same lanes active (a regrouping only
      // the identity check can tell), from pass g_testRepackPass on (the renderer: 0, so
      // every tile computation is given up before anything is stored).
      if (testRepackHere && gl_SubgroupInvocationID >= gl_SubgroupSize / 2u &&
          pass >= g_testRepackPass)
        firstBefore += 1u;
#endif
      bool stable = subgroupAll(gl_SubgroupInvocationID == lane) &&
                    subgroupAllEqual(firstBefore) &&
                    all(equal(subgroupBallot(true), activeLanes));
      if (!stable) {
        g_tileRepacks += 1u;
        if (request && !served) g_tileFallbacks += 1u;
        if (entry >= 0)
          tileGiveUp(uint(entry), lockKey, evicted, lockedPlace, pass, activeCount);
        served = false;
        return;
      }
#endif
      if (worker) {
        // Only locked tiles have workers. Store, release fence, count (tileCountTexels): the
        // lane whose add completes the tile publishes it, in whatever pass that happens.
        tileStoreTexel(uint(tileEntry), texel, texelValues);
        tileStorageBarrier();
        tileCountTexels(uint(tileEntry), tileKey, 1u);
      }
      [[unroll]] for (uint t = 0u; t < kTileTaps; ++t) {
        uint wanted = myComputed * kTileTexels + taps[t];
        bool here = mine && wanted / activeCount == pass;
        float tap[MG_CACHE_VALUES];
        tileShuffleValues(texelValues, here ? laneOfRank(activeLanes, wanted % activeCount) : lane,
                          tap);
        if (here)
          for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) filtered[i] += weights[t] * tap[i];
      }
    }
    // Step 7 happened in the passes: each tile's last texel published it (tileCountTexels),
    // with no subgroup operation in the memory ordering, so it does not depend on how the
    // driver reconverges the lanes either (VK_KHR_shader_maximal_reconvergence would not
    // change it). Not subgroupBarrier(): lavapipe runs it as a work-group barrier, which
    // corrupted state when the subgroups of a work group looped here a different number of
    // times.
    if (mine) {
      values = filtered;
      served = true;
    }
  }
}

#endif  // MG_TILE_FILL_DEFERRED

#ifndef MG_WAVEFRONT
// The tile cache's material evaluation. Every lane of the subgroup calls it at the same
// point; `hasHit` is false for lanes without a hit (their outputs are meaningless).
// Cacheable materials read their tile; the subgroup computes the missing tiles together;
// other materials (and lanes the subgroup could not serve) are evaluated directly.
void evaluateMaterialTiled(bool hasHit, uint materialId, MaterialInputs inputs,
                           out MaterialOutputs outputs) {
#ifdef MG_TILE_TEST_PARTIAL_SUBGROUPS
  // Test hook: odd lanes leave here, so the rest compute tiles in a partial subgroup (as
  // NVIDIA's raygen often has them), with several passes per tile when needed.
  if ((gl_SubgroupInvocationID & 1u) == 1u) {
    if (hasHit) evaluateMaterialDirect(materialId, inputs, outputs);
    else outputs = mg_defaultMaterialOutputs(inputs);
    return;
  }
#endif
  uvec4 info = hasHit ? cacheInfoOf(materialId) : uvec4(0u);
  TileRequest tile;
  bool cached = info.x != 0u && frame.cache.x != 0u && tileRequestFor(info, inputs, tile);
  if (!cached) {
    tile.key.base = 0u;
    tile.key.hash = 0u;
    tile.level = 0;
    tile.tile = vec2(0.0);
    tile.local = vec2(0.0);
  }
  float values[MG_CACHE_VALUES];
  bool request = false;
  if (cached) {
    g_cacheLookups += 1u;
    if (tileRead(tile, values)) {
      g_cacheHits += 1u;
    } else {
      g_cacheMisses += 1u;
      g_cacheMissed = true;
      request = true;
    }
  } else {
    for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;
  }
  bool served = false;
#ifdef MG_TILE_FILL_DEFERRED
  if (request) tileEnqueue(materialId, tile);
#else
  tileComputeMissing(request, materialId, info, tile, inputs, values, served);
#endif
  if (cached && (!request || served)) {
    outputs = cacheUnpack(info.x, values, inputs);
  } else if (hasHit) {
    evaluateMaterialDirect(materialId, inputs, outputs);
  } else {
    outputs = mg_defaultMaterialOutputs(inputs);
  }
}

#endif  // MG_WAVEFRONT

#endif
