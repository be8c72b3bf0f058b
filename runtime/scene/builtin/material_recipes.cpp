#include "runtime/scene/builtin/material_recipes.h"

#include "runtime/scene/builtin/material_builder.h"

namespace memograph::runtime {
namespace {

// Mixes `cost.layers` further multi-octave noise layers into `color`, each pulling it a
// little towards `tint` at its own frequency: the knob that makes a material heavier
// without changing its look much.
GraphLink addDetailLayers(MaterialBuilder& b, GraphLink uv, GraphLink color, glm::vec3 tint,
                          float baseScale, MaterialCost cost) {
  for (int i = 0; i < cost.layers; ++i) {
    const float scale = baseScale * static_cast<float>(3 + 2 * i);
    const GraphLink p = b.transformUv(uv, {1.0f, 1.0f}, {17.0f * i + 3.1f, 5.3f * i});
    const GraphLink n = b.noise(p, scale, cost.octaves, 0.55f);
    color = b.mix(b.multiply(n, 0.35f), color, tint);
  }
  return color;
}

}  // namespace

glm::vec2 RecipeSeed::offset() const {
  // A cheap integer hash spread over [0, 16) UV units: enough for two seeds to show
  // different noise, and small enough that a texture's coordinates (offset × a Scale of up
  // to a few hundred) keep float precision on the GPU: at offsets of hundreds of units a
  // float's step would approach the size of a fine noise feature.
  std::uint32_t h = value * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return {static_cast<float>(h & 0xffffu) / 65536.0f * 16.0f,
          static_cast<float>(h >> 16u) / 65536.0f * 16.0f};
}

std::string woodGraph(const std::string& name, const WoodParams& p, RecipeSeed seed,
                      MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.uv();
  // Grain: noise stretched along u, turned into growth rings by taking the fraction of a
  // multiple of it.
  const GraphLink grainUv = b.transformUv(uv, {1.0f, p.grainStretch}, seed.offset());
  const GraphLink rings =
      b.fraction(b.multiply(b.noise(grainUv, 1.5f, cost.octaves, 0.5f), p.ringFrequency));
  GraphLink color = b.ramp(rings, 0.1f, p.light, 0.9f, p.dark);
  const GraphLink fibres = b.noise(grainUv, 24.0f, cost.octaves, 0.6f);
  color = b.mix(b.multiply(fibres, 0.4f), color, p.dark * 0.8f);
  color = addDetailLayers(b, uv, color, p.light * 0.9f, 4.0f, cost);
  b.baseColor(color);
  b.roughness(b.mix(fibres, p.roughness - 0.1f, p.roughness + 0.15f));
  return b.text();
}

std::string paintedMetalGraph(const std::string& name, const PaintedMetalParams& p, RecipeSeed seed,
                              MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  // Wear: large blotches where the noise exceeds 1 - wear, chipped at their edges by
  // voronoi cells.
  const GraphLink blotch = b.noise(uv, 3.0f, cost.octaves, 0.6f);
  const GraphLink chips = b.voronoiDistance(uv, 40.0f);
  const GraphLink worn = b.mapRange(blotch, 1.0f - p.wear - 0.05f, 1.0f - p.wear + 0.05f);
  GraphLink color =
      b.mix(b.multiply(chips, 0.3f), b.mix(blotch, p.paint, p.paint * 0.85f), p.paint * 0.6f);
  const GraphLink scratched = b.mix(b.noise(uv, 9.0f, cost.octaves, 0.5f), p.metal * 0.8f, p.metal);
  color = b.mix(worn, color, scratched);
  color = addDetailLayers(b, uv, color, p.paint * 0.7f, 6.0f, cost);
  b.baseColor(color);
  b.metallic(b.mix(worn, 0.0f, 1.0f));
  b.roughness(b.mix(b.noise(uv, 30.0f, cost.octaves, 0.5f), 0.3f, 0.55f));
  return b.text();
}

std::string plasticGraph(const std::string& name, const PlasticParams& p, RecipeSeed seed,
                         MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const GraphLink mottling = b.noise(uv, 5.0f, cost.octaves, 0.5f);
  const GraphLink speckles = b.voronoiDistance(uv, 80.0f);
  GraphLink color = b.mix(b.multiply(mottling, 0.3f), p.color, p.color * 0.75f);
  color = b.mix(b.multiply(speckles, p.speckle), color, glm::vec3(0.9f));
  color = addDetailLayers(b, uv, color, p.color * 0.85f, 12.0f, cost);
  b.baseColor(color);
  b.roughness(
      b.mix(b.noise(uv, 40.0f, cost.octaves, 0.5f), p.roughness - 0.1f, p.roughness + 0.1f));
  return b.text();
}

std::string fabricGraph(const std::string& name, const FabricParams& p, RecipeSeed seed,
                        MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  // Weave: a fine checker decides warp or weft; fibres are noise stretched along each.
  const GraphLink weave = b.checker(uv, p.threadsPerMetre);
  const GraphLink warpFibres =
      b.noise(b.transformUv(uv, {1.0f, 12.0f}, {0, 0}), 20.0f, cost.octaves, 0.6f);
  const GraphLink weftFibres =
      b.noise(b.transformUv(uv, {12.0f, 1.0f}, {0, 0}), 20.0f, cost.octaves, 0.6f);
  const GraphLink warp = b.mix(warpFibres, p.warp * 0.7f, p.warp);
  const GraphLink weft = b.mix(weftFibres, p.weft * 0.7f, p.weft);
  GraphLink color = b.mix(weave, warp, weft);
  color = addDetailLayers(b, uv, color, (p.warp + p.weft) * 0.4f, 3.0f, cost);
  b.baseColor(color);
  b.roughness(0.9f);
  return b.text();
}

std::string tileGraph(const std::string& name, const TileParams& p, RecipeSeed seed,
                      MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const float tilesPerMetre = 1.0f / p.tileSize;
  const GraphLink mortar = b.brick(uv, tilesPerMetre, p.checker ? 0.03f : 0.05f);
  GraphLink tile;
  if (p.checker) {
    tile = b.mix(b.checker(uv, tilesPerMetre * 0.5f), p.tileA, p.tileB);
  } else {
    tile = b.mix(b.noise(uv, tilesPerMetre, 2, 0.5f), p.tileA, p.tileA * 0.9f);
  }
  // Per-tile tone variation from voronoi cells at tile frequency, and dirt.
  tile = b.mix(b.multiply(b.voronoiDistance(uv, tilesPerMetre), 0.2f), tile, p.tileA * 0.8f);
  const GraphLink dirt = b.noise(uv, 2.0f, cost.octaves, 0.6f);
  tile = b.mix(b.multiply(dirt, 0.3f), tile, p.grout * 0.6f);
  tile = addDetailLayers(b, uv, tile, p.tileA * 0.9f, 8.0f, cost);
  b.baseColor(b.mix(mortar, tile, p.grout));
  b.roughness(b.mix(mortar, 0.25f, 0.9f));
  return b.text();
}

std::string plasterGraph(const std::string& name, const PlasterParams& p, RecipeSeed seed,
                         MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const GraphLink blotches = b.noise(uv, 1.5f, cost.octaves, 0.55f);
  const GraphLink grain = b.noise(uv, 60.0f, cost.octaves, 0.7f);
  GraphLink color = b.mix(b.multiply(blotches, 0.3f), p.color, p.color * 0.85f);
  color = b.mix(b.multiply(grain, 0.2f), color, p.color * 0.7f);
  color = addDetailLayers(b, uv, color, p.color * 0.9f, 5.0f, cost);
  b.baseColor(color);
  b.roughness(b.mix(grain, p.roughness - 0.1f, p.roughness + 0.1f));
  return b.text();
}

std::string chalkboardGraph(const std::string& name, const ChalkboardParams& p, RecipeSeed seed,
                            MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  // Wiped chalk: broad horizontal smears plus fine dust.
  const GraphLink smears =
      b.noise(b.transformUv(uv, {0.3f, 2.0f}, {0, 0}), 2.0f, cost.octaves, 0.6f);
  const GraphLink dust = b.noise(uv, 50.0f, cost.octaves, 0.6f);
  GraphLink color = b.mix(b.multiply(smears, 0.25f), p.board, p.chalk);
  color = b.mix(b.multiply(dust, 0.1f), color, p.chalk);
  color = addDetailLayers(b, uv, color, p.board * 0.8f, 7.0f, cost);
  b.baseColor(color);
  b.roughness(b.mix(smears, 0.6f, 0.9f));
  return b.text();
}

std::string leatherGraph(const std::string& name, const LeatherParams& p, RecipeSeed seed,
                         MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  // Leather grain: small voronoi cells, their borders darker, over mottled noise.
  const GraphLink cells = b.voronoiDistance(uv, 150.0f);
  const GraphLink mottling = b.noise(uv, 8.0f, cost.octaves, 0.55f);
  GraphLink color = b.mix(b.multiply(mottling, 0.4f), p.color, p.color * 0.6f);
  color = b.mix(b.multiply(cells, 0.5f), color, p.color * 1.2f);
  color = addDetailLayers(b, uv, color, p.color * 0.7f, 10.0f, cost);
  b.baseColor(color);
  b.roughness(b.mix(cells, p.roughness - 0.15f, p.roughness + 0.1f));
  return b.text();
}

std::string posterGraph(const std::string& name, const PosterParams& p, RecipeSeed seed,
                        MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  // An abstract print: coloured voronoi cells blended between two inks, faded by noise.
  const GraphLink cells = b.voronoiColor(uv, p.cellsPerMetre);
  const GraphLink shapes = b.noise(uv, p.cellsPerMetre * 0.5f, cost.octaves, 0.5f);
  GraphLink color = b.mix(shapes, p.a, p.b);
  color = b.mix(b.checker(uv, p.cellsPerMetre * 2.0f), color, cells);
  color = b.mix(b.multiply(b.noise(uv, 30.0f, cost.octaves, 0.6f), 0.3f), color, p.paper);
  color = addDetailLayers(b, uv, color, p.paper, 9.0f, cost);
  b.baseColor(color);
  b.roughness(0.7f);
  return b.text();
}

std::string corkGraph(const std::string& name, const CorkParams& p, RecipeSeed seed,
                      MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const GraphLink granules = b.voronoiDistance(uv, 300.0f);
  const GraphLink tone = b.noise(uv, 40.0f, cost.octaves, 0.7f);
  GraphLink color = b.mix(tone, p.color * 0.7f, p.color * 1.15f);
  color = b.mix(b.multiply(granules, 0.6f), color, p.color * 0.4f);
  color = addDetailLayers(b, uv, color, p.color * 0.8f, 20.0f, cost);
  b.baseColor(color);
  b.roughness(0.95f);
  return b.text();
}

std::string missingMaterialGraph(const std::string& name) {
  MaterialBuilder b(name);
  b.baseColor(b.mix(b.checker(b.uv(), 5.0f), glm::vec3(1.0f, 0.0f, 1.0f), glm::vec3(0.02f)));
  b.roughness(0.6f);
  return b.text();
}

std::string emitterGraph(const std::string& name, const EmitterParams& p) {
  MaterialBuilder b(name);
  b.baseColor(p.baseColor);
  b.emission(p.radiance);
  b.roughness(0.5f);
  return b.text();
}

std::string mirrorGraph(const std::string& name) {
  MaterialBuilder b(name);
  b.baseColor(glm::vec3(0.92f, 0.92f, 0.9f));
  b.metallic(1.0f);
  b.roughness(0.02f);
  return b.text();
}

std::string terrainGraph(const std::string& name, const TerrainParams& p, MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.uv();
  const float perMetre = p.metresPerUv;  // noise Scale s over UV = s / metresPerUv per metre
  // Layers, each with its own multi-octave detail.
  const GraphLink grassNoise = b.noise(uv, 1.5f * perMetre, cost.octaves, 0.6f);
  const GraphLink grass =
      b.mix(grassNoise, glm::vec3(0.10f, 0.22f, 0.05f), glm::vec3(0.28f, 0.38f, 0.10f));
  const GraphLink dirtNoise =
      b.noise(b.transformUv(uv, {1, 1}, {31.0f, 7.0f}), 0.8f * perMetre, cost.octaves, 0.55f);
  const GraphLink dirt =
      b.mix(dirtNoise, glm::vec3(0.22f, 0.16f, 0.10f), glm::vec3(0.40f, 0.31f, 0.21f));
  const GraphLink rockCells = b.voronoiDistance(uv, 0.5f * perMetre);
  const GraphLink rockNoise =
      b.noise(b.transformUv(uv, {1, 1}, {-13.0f, 57.0f}), 2.0f * perMetre, cost.octaves, 0.65f);
  const GraphLink rock = b.mix(
      rockNoise, b.mix(rockCells, glm::vec3(0.42f, 0.40f, 0.37f), glm::vec3(0.25f, 0.24f, 0.22f)),
      glm::vec3(0.55f, 0.53f, 0.5f));
  const GraphLink snowNoise = b.noise(uv, 3.0f * perMetre, cost.octaves, 0.5f);
  const GraphLink snow =
      b.mix(snowNoise, glm::vec3(0.82f, 0.84f, 0.88f), glm::vec3(0.95f, 0.96f, 0.98f));
  // Masks: noise with features of ~50–200 m stands in for height and slope (see header).
  const GraphLink dirtMask = b.mapRange(
      b.noise(b.transformUv(uv, {1, 1}, {5.0f, 11.0f}), perMetre / 60.0f, cost.octaves, 0.5f),
      0.45f, 0.6f);
  const GraphLink rockMask = b.mapRange(
      b.noise(b.transformUv(uv, {1, 1}, {-41.0f, 3.0f}), perMetre / 120.0f, cost.octaves, 0.5f),
      0.5f, 0.62f);
  const GraphLink snowMask = b.mapRange(
      b.noise(b.transformUv(uv, {1, 1}, {77.0f, -19.0f}), perMetre / 200.0f, cost.octaves, 0.5f),
      0.6f, 0.68f);
  GraphLink color = b.mix(dirtMask, grass, dirt);
  color = b.mix(rockMask, color, rock);
  color = b.mix(snowMask, color, snow);
  color = addDetailLayers(b, uv, color, glm::vec3(0.2f, 0.18f, 0.12f), 4.0f * perMetre, cost);
  b.baseColor(color);
  b.roughness(b.mix(rockNoise, 0.7f, 0.95f));
  return b.text();
}

std::string rockGraph(const std::string& name, const RockParams& p, RecipeSeed seed,
                      MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const GraphLink cells = b.voronoiDistance(uv, 3.0f);
  const GraphLink grain = b.noise(uv, 12.0f, cost.octaves, 0.65f);
  GraphLink color = b.mix(cells, p.light, p.dark);
  color = b.mix(b.multiply(grain, 0.5f), color, p.light * 1.1f);
  b.baseColor(color);
  b.roughness(b.mix(grain, 0.7f, 0.95f));
  return b.text();
}

std::string barkGraph(const std::string& name, const BarkParams& p, RecipeSeed seed,
                      MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {6.0f, 1.0f}, seed.offset());
  const GraphLink furrows = b.noise(uv, 4.0f, cost.octaves, 0.6f);
  b.baseColor(b.mix(furrows, p.color * 0.5f, p.color * 1.3f));
  b.roughness(0.9f);
  return b.text();
}

std::string foliageGraph(const std::string& name, const FoliageParams& p, RecipeSeed seed,
                         MaterialCost cost) {
  MaterialBuilder b(name, cost.ambientOcclusionSamples, cost.bevelSamples);
  const GraphLink uv = b.transformUv(b.uv(), {1.0f, 1.0f}, seed.offset());
  const GraphLink leaves = b.voronoiDistance(uv, 25.0f);
  const GraphLink tone = b.noise(uv, 3.0f, cost.octaves, 0.5f);
  b.baseColor(b.mix(leaves, b.mix(tone, p.dark, p.light), p.dark * 0.6f));
  b.roughness(0.75f);
  return b.text();
}

}  // namespace memograph::runtime
