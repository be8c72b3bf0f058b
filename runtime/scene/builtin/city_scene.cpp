// The city built-in scene: a large instanced scene where acceleration-structure memory and
// culling matter (the culling paper's setting, seeds/001 §3.3): a grid of blocks on gentle
// hills, thousands of buildings each with its own terrain-fitted geometry (its own BLAS),
// tens of thousands of shared props (trees, street lamps, cars, benches), flags whose cloth
// moves every frame (their own meshes: a BLAS each to update), and a mirror wall at the end
// of the main street that shows what is behind the camera. `scale` shrinks the counts
// together (and the grid with them), so that scale 0.02 renders on lavapipe in seconds.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/builtin/mesh_lods.h"
#include "runtime/scene/builtin/procedural.h"
#include "runtime/scene/builtin/scene_builder.h"

namespace memograph::runtime {
namespace {

constexpr float kFloorHeight = 3.2f;
constexpr float kWindowWidth = 1.4f, kWindowHeight = 1.8f, kWindowSpacing = 3.0f;
constexpr float kWindowDepth = 0.18f;  // how far a window's frame stands out of the wall

// Appends one wall's windows, each as six boxes (sill, lintel, two jambs, a mullion and the
// recessed pane), per window per floor, along the wall from `start` in direction `along`
// (unit, axis-aligned), the frames standing out towards `outward`. The windows are most of
// a building's triangles: the geometry that makes the city's BLASes large.
void appendWindows(Mesh& mesh, glm::vec3 start, glm::vec3 along, glm::vec3 outward, float length,
                   float bottom, int floors) {
  const int count = std::max(0, static_cast<int>((length - 1.0f) / kWindowSpacing));
  if (count == 0)
    return;
  const float margin = 0.5f * (length - static_cast<float>(count) * kWindowSpacing);
  // A box spanning [s0, s1] along the wall, [y0, y1] up and [o0, o1] out of it.
  const auto box = [&](float s0, float s1, float y0, float y1, float o0, float o1) {
    const glm::vec3 a = start + along * s0 + outward * o0;
    const glm::vec3 b = start + along * s1 + outward * o1;
    appendBox(mesh, {std::min(a.x, b.x), y0, std::min(a.z, b.z)},
              {std::max(a.x, b.x), y1, std::max(a.z, b.z)}, UvScale{1.0f});
  };
  constexpr float kFrame = 0.12f;
  for (int f = 0; f < floors; ++f) {
    const float y0 = bottom + static_cast<float>(f) * kFloorHeight + 0.8f;
    const float y1 = y0 + kWindowHeight;
    for (int w = 0; w < count; ++w) {
      const float s = margin + (static_cast<float>(w) + 0.5f) * kWindowSpacing;
      const float s0 = s - 0.5f * kWindowWidth, s1 = s + 0.5f * kWindowWidth;
      box(s0 - 0.05f, s1 + 0.05f, y0 - kFrame, y0, 0.0f, kWindowDepth + 0.05f);  // sill
      box(s0, s1, y1 - kFrame, y1, 0.0f, kWindowDepth);                          // lintel
      box(s0, s0 + kFrame, y0, y1 - kFrame, 0.0f, kWindowDepth);                 // jambs
      box(s1 - kFrame, s1, y0, y1 - kFrame, 0.0f, kWindowDepth);
      box(s - 0.5f * kFrame, s + 0.5f * kFrame, y0, y1 - kFrame, 0.0f, 0.6f * kWindowDepth);
      box(s0 + kFrame, s1 - kFrame, y0, y1 - kFrame, -0.12f, -0.08f);  // the pane, set in
    }
  }
}

// One building in lot-local coordinates (the lot's centre at x = z = 0 and the terrain
// height there at y = 0): a plinth down to the lowest ground under the footprint (the
// terrain-fitted part), the body, a frame per window per floor, and a roof structure.
Mesh buildingMesh(int index, float width, float depth, int floors, float groundLow,
                  float groundHigh, std::uint32_t seed) {
  Mesh mesh;
  mesh.name = "building_" + std::to_string(index);
  const float hx = 0.5f * width, hz = 0.5f * depth;
  const float plinthTop = groundHigh + 0.6f;
  appendBox(mesh, {-hx - 0.3f, groundLow - 1.0f, -hz - 0.3f}, {hx + 0.3f, plinthTop, hz + 0.3f},
            UvScale{1.0f});
  const float top = plinthTop + static_cast<float>(floors) * kFloorHeight;
  appendBox(mesh, {-hx, plinthTop, -hz}, {hx, top, hz}, UvScale{1.0f});
  appendWindows(mesh, {-hx, 0, hz}, {1, 0, 0}, {0, 0, 1}, width, plinthTop, floors);
  appendWindows(mesh, {hx, 0, -hz}, {-1, 0, 0}, {0, 0, -1}, width, plinthTop, floors);
  appendWindows(mesh, {hx, 0, hz}, {0, 0, -1}, {1, 0, 0}, depth, plinthTop, floors);
  appendWindows(mesh, {-hx, 0, -hz}, {0, 0, 1}, {-1, 0, 0}, depth, plinthTop, floors);
  // A setback storey or a plant room, placed by the building's own hash.
  const float sx = hx * (0.3f + 0.4f * hash2(index, 1, seed));
  const float sz = hz * (0.3f + 0.4f * hash2(index, 2, seed));
  const float ox = (hash2(index, 3, seed) - 0.5f) * (hx - sx);
  const float oz = (hash2(index, 4, seed) - 0.5f) * (hz - sz);
  const float roof = kFloorHeight * (0.6f + 1.2f * hash2(index, 5, seed));
  appendBox(mesh, {ox - sx, top, oz - sz}, {ox + sx, top + roof, oz + sz}, UvScale{1.0f});
  return mesh;
}

// A flag's cloth: its length along +x from the pole, which its wave grows over.
constexpr float kFlagWidth = 2.4f;

// A flag's cloth at rest: a (cells+1) x (rows+1) grid in the x-y plane, hanging from x = 0.
Mesh flagMesh(int index) {
  Mesh mesh;
  mesh.name = "flag_" + std::to_string(index);
  constexpr int kColumns = 8, kRows = 5;
  constexpr float kWidth = kFlagWidth, kHeight = 1.5f;
  for (int r = 0; r <= kRows; ++r) {
    for (int c = 0; c <= kColumns; ++c) {
      const float u = static_cast<float>(c) / kColumns, v = static_cast<float>(r) / kRows;
      mesh.positions.push_back({u * kWidth, v * kHeight, 0.0f});
      mesh.normals.push_back({0.0f, 0.0f, 1.0f});
      mesh.uvs.push_back({u * kWidth, v * kHeight});
    }
  }
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kColumns; ++c) {
      const auto i = static_cast<std::uint32_t>(r * (kColumns + 1) + c);
      const auto row = static_cast<std::uint32_t>(kColumns + 1);
      mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + row, i + 1, i + row + 1, i + row});
    }
  }
  return mesh;
}

struct CityLayout {
  int blocksPerSide = 0;
  float halfSize = 0;  // the city covers [-halfSize, halfSize]² in x and z
};

CityLayout cityLayout(double scale) {
  CityLayout layout;
  // An even count, so that a street runs along x = 0 (the main street).
  layout.blocksPerSide = 2 * std::max(1, static_cast<int>(std::lround(6.0 * std::sqrt(scale))));
  layout.halfSize = 0.5f * static_cast<float>(layout.blocksPerSide) * kCityBlockSize;
  return layout;
}

}  // namespace

float cityTerrainHeight(float x, float z) {
  // Gentle hills (a few metres), so that buildings need terrain-fitted plinths.
  return 6.0f * fbm(x / 300.0f, z / 300.0f, 4, 41u) + 2.0f * std::sin(x / 170.0f);
}

CityCounts cityCounts(double scale) {
  if (!(scale > 0.0 && scale <= 1.0))
    throw std::invalid_argument("builtin city: scale must be in (0, 1], got " +
                                std::to_string(scale));
  CityCounts counts;
  counts.buildings = std::max(1, static_cast<int>(std::lround(2000.0 * scale)));
  counts.props = std::max(1, static_cast<int>(std::lround(18500.0 * scale)));
  counts.flags = std::max(1, static_cast<int>(std::lround(300.0 * scale)));
  return counts;
}

float cityHalfSize(double scale) {
  return cityLayout(scale).halfSize;
}

namespace {

// The city's materials: facades in several plasters, road and pavement tiles, the ground,
// props' paint, bark and leaves, flag cloth, and the mirror.
struct CityMaterials {
  std::uint32_t facades[6] = {};
  std::uint32_t ground = 0, pavement = 0, metal = 0, carPaint = 0, bark = 0, leaves = 0, cloth = 0,
                mirror = 0;
};

CityMaterials addCityMaterials(SceneBuilder& b, const MaterialCost& cost) {
  // Half the octaves and no layers; the traced inputs as the others.
  const MaterialCost light{std::max(1, cost.octaves / 2), 0, cost.ambientOcclusionSamples,
                           cost.bevelSamples};
  CityMaterials m;
  const glm::vec3 facadeColours[6] = {{0.82f, 0.78f, 0.70f}, {0.70f, 0.55f, 0.45f},
                                      {0.60f, 0.62f, 0.66f}, {0.85f, 0.84f, 0.80f},
                                      {0.55f, 0.45f, 0.38f}, {0.75f, 0.70f, 0.55f}};
  for (int i = 0; i < 6; ++i) {
    const std::string name = "City_Facade_" + std::to_string(i);
    m.facades[i] =
        b.material(name, plasterGraph(name, {facadeColours[i], 0.8f},
                                      RecipeSeed{300u + static_cast<std::uint32_t>(i)}, cost));
  }
  m.ground = b.material("City_Ground", terrainGraph("City_Ground", TerrainParams{}, light));
  TileParams pavementTiles;
  pavementTiles.tileA = {0.45f, 0.45f, 0.46f};
  pavementTiles.tileB = {0.38f, 0.38f, 0.40f};
  pavementTiles.grout = {0.25f, 0.25f, 0.26f};
  pavementTiles.tileSize = 0.6f;
  m.pavement = b.material("City_Pavement",
                          tileGraph("City_Pavement", pavementTiles, RecipeSeed{310}, light));
  m.metal = b.material("City_Metal", paintedMetalGraph("City_Metal", {}, RecipeSeed{311}, light));
  m.carPaint =
      b.material("City_CarPaint", plasticGraph("City_CarPaint", {}, RecipeSeed{312}, light));
  m.bark = b.material("City_Bark", barkGraph("City_Bark", {}, RecipeSeed{313}, light));
  m.leaves = b.material("City_Foliage", foliageGraph("City_Foliage", {}, RecipeSeed{314}, light));
  m.cloth = b.material("City_Flag", fabricGraph("City_Flag", {}, RecipeSeed{315}, light));
  m.mirror = b.material("City_Mirror", mirrorGraph("City_Mirror"));

  return m;
}

// A lot a building may stand on; lots are filled in `order`.
struct Lot {
  glm::vec2 centre;
  float order;
};

// The ground, then a pavement slab per block; returns the blocks' lots in filling order.
std::vector<Lot> addGroundAndLots(SceneBuilder& b, const CityLayout& layout,
                                  const CityMaterials& m) {
  const float half = layout.halfSize;
  const int cells = std::clamp(layout.blocksPerSide * 16, 32, 512);
  b.instance(b.addMesh(makeHeightfield("city_ground", -half - 100.0f, -half - 100.0f, half + 100.0f,
                                       half + 100.0f, cells, cityTerrainHeight, UvScale{8.0f})),
             m.ground, glm::mat4(1.0f));

  // Lots: each block (kCityBlockSize, a street of kCityStreetWidth around it) holds a 4 x 4
  // grid of lots; buildings fill lots in a hashed order, so a smaller scale thins the city
  // evenly instead of emptying its edge.
  const int lotsPerBlock = 4;
  const float blockInner = kCityBlockSize - kCityStreetWidth;
  const float lotSize = blockInner / static_cast<float>(lotsPerBlock);
  std::vector<Lot> lots;
  for (int bx = 0; bx < layout.blocksPerSide; ++bx) {
    for (int bz = 0; bz < layout.blocksPerSide; ++bz) {
      const float x0 = -half + static_cast<float>(bx) * kCityBlockSize + 0.5f * kCityStreetWidth;
      const float z0 = -half + static_cast<float>(bz) * kCityBlockSize + 0.5f * kCityStreetWidth;
      // A pavement slab per block, following the terrain at its centre.
      const float cx = x0 + 0.5f * blockInner, cz = z0 + 0.5f * blockInner;
      Mesh slab;
      slab.name = "pavement_" + std::to_string(bx) + "_" + std::to_string(bz);
      appendBox(slab, {-0.5f * blockInner - 2.0f, -1.5f, -0.5f * blockInner - 2.0f},
                {0.5f * blockInner + 2.0f, 0.15f, 0.5f * blockInner + 2.0f}, UvScale{1.0f});
      b.instance(b.addMesh(std::move(slab)), m.pavement,
                 placed({cx, cityTerrainHeight(cx, cz), cz}, 0.0f, 1.0f));
      for (int lx = 0; lx < lotsPerBlock; ++lx)
        for (int lz = 0; lz < lotsPerBlock; ++lz)
          lots.push_back({{x0 + (static_cast<float>(lx) + 0.5f) * lotSize,
                           z0 + (static_cast<float>(lz) + 0.5f) * lotSize},
                          hash2(bx * lotsPerBlock + lx, bz * lotsPerBlock + lz, 51u)});
    }
  }
  std::stable_sort(lots.begin(), lots.end(),
                   [](const Lot& a, const Lot& c) { return a.order < c.order; });

  return lots;
}

// Returns the buildings' meshes (each its own: their LODs pay, seeds/001 §3.3.1).
std::vector<std::uint32_t> addBuildings(SceneBuilder& b, const CityLayout& layout,
                                        const CityCounts& counts, const std::vector<Lot>& lots,
                                        const CityMaterials& m) {
  std::vector<std::uint32_t> meshes;
  const float half = layout.halfSize;
  const float lotSize = (kCityBlockSize - kCityStreetWidth) / 4.0f;  // 4 x 4 lots a block
  // Buildings: taller towards the centre; every one its own mesh. Lots are reused (with a
  // smaller footprint on top: a tower on a podium's lot) when there are more buildings than
  // lots, which only the largest scales reach.
  for (int i = 0; i < counts.buildings; ++i) {
    const Lot& lot = lots[static_cast<std::size_t>(i) % lots.size()];
    const float shrink = i < static_cast<int>(lots.size()) ? 1.0f : 0.55f;
    const float width = shrink * lotSize * (0.55f + 0.35f * hash2(i, 10, 61u));
    const float depth = shrink * lotSize * (0.55f + 0.35f * hash2(i, 11, 61u));
    const float centrality = 1.0f - glm::length(lot.centre) / (half * 1.42f);
    const int floors =
        2 + static_cast<int>(std::floor(
                (3.0f + 22.0f * centrality * centrality) * hash2(i, 12, 61u) + 4.0f * centrality));
    const float y = cityTerrainHeight(lot.centre.x, lot.centre.y);
    float low = 0.0f, high = 0.0f;
    for (int c = 0; c < 4; ++c) {
      const float cx = lot.centre.x + (c & 1 ? 0.5f : -0.5f) * width;
      const float cz = lot.centre.y + (c & 2 ? 0.5f : -0.5f) * depth;
      const float h = cityTerrainHeight(cx, cz) - y;
      low = std::min(low, h);
      high = std::max(high, h);
    }
    const auto mesh = b.addMesh(buildingMesh(i, width, depth, floors, low, high, 71u));
    b.instance(mesh, m.facades[static_cast<int>(hash2(i, 13, 61u) * 6.0f) % 6],
               placed({lot.centre.x, y, lot.centre.y}, 0.0f, 1.0f));
    meshes.push_back(mesh);
  }
  return meshes;
}

void addProps(SceneBuilder& b, const CityLayout& layout, const CityCounts& counts,
              const CityMaterials& mat) {
  const float half = layout.halfSize;
  // Shared props along the streets: one mesh each, instanced many times.
  Mesh lamp;
  lamp.name = "street_lamp";
  appendCylinder(lamp, {0, 0, 0}, 0.09f, 5.5f, 10);
  appendBox(lamp, {-0.15f, 5.5f, -0.15f}, {0.9f, 5.7f, 0.15f});
  const auto lampMesh = b.addMesh(std::move(lamp));
  Mesh car;
  car.name = "car";
  appendBox(car, {-0.9f, 0.3f, -2.1f}, {0.9f, 1.0f, 2.1f});
  appendBox(car, {-0.8f, 1.0f, -1.1f}, {0.8f, 1.5f, 0.9f});
  const auto carMesh = b.addMesh(std::move(car));
  Mesh bench;
  bench.name = "bench";
  appendBox(bench, {-0.9f, 0.4f, -0.25f}, {0.9f, 0.48f, 0.25f});
  appendBox(bench, {-0.9f, 0.48f, 0.2f}, {0.9f, 0.9f, 0.25f});
  appendBox(bench, {-0.85f, 0.0f, -0.2f}, {-0.75f, 0.4f, 0.2f});
  appendBox(bench, {0.75f, 0.0f, -0.2f}, {0.85f, 0.4f, 0.2f});
  const auto benchMesh = b.addMesh(std::move(bench));
  Mesh trunk;
  trunk.name = "street_tree_trunk";
  appendCylinder(trunk, {0, -0.3f, 0}, 0.18f, 3.2f, 10);
  const auto trunkMesh = b.addMesh(std::move(trunk));
  Mesh crown;
  crown.name = "street_tree_crown";
  appendDeformedSphere(
      crown, {0, 4.2f, 0}, {1.8f, 1.6f, 1.8f}, 10, 16,
      [](glm::vec3 d) { return 0.85f + 0.3f * valueNoise(d.x * 3.0f, d.z * 3.0f + d.y, 81u); },
      UvScale{1.0f});
  const auto crownMesh = b.addMesh(std::move(crown));

  // Props stand on the streets' edges: pick a street line and a position along it.
  const int lines = layout.blocksPerSide + 1;
  for (int i = 0; i < counts.props;) {
    const bool alongX = hash2(i, 20, 91u) < 0.5f;
    const int line = static_cast<int>(hash2(i, 21, 91u) * static_cast<float>(lines)) % lines;
    const float across = -half + static_cast<float>(line) * kCityBlockSize +
                         (hash2(i, 22, 91u) < 0.5f ? -1.0f : 1.0f) * 0.5f * kCityStreetWidth *
                             (0.55f + 0.3f * hash2(i, 23, 91u));
    const float along = (hash2(i, 24, 91u) * 2.0f - 1.0f) * half;
    const float x = alongX ? along : across, z = alongX ? across : along;
    const float yaw = alongX ? 0.0f : 1.5707963f;
    const glm::mat4 m = placed({x, cityTerrainHeight(x, z), z}, yaw, 1.0f);
    const float kind = hash2(i, 25, 91u);
    if (kind < 0.3f) {
      b.instance(lampMesh, mat.metal, m);
      ++i;
    } else if (kind < 0.55f) {
      b.instance(carMesh, mat.carPaint, m);
      ++i;
    } else if (kind < 0.7f) {
      b.instance(benchMesh, mat.metal, m);
      ++i;
    } else {
      b.instance(trunkMesh, mat.bark, m);
      b.instance(crownMesh, mat.leaves, m);
      i += 2;
    }
  }
}

void addFlags(SceneBuilder& b, const CityLayout& layout, const CityCounts& counts,
              const CityMaterials& m) {
  const float half = layout.halfSize;
  const int lines = layout.blocksPerSide + 1;
  // Flags on poles around the squares: every cloth its own mesh (it moves every frame, see
  // cityFlagMotion), every pole a shared prop.
  Mesh pole;
  pole.name = "flag_pole";
  appendCylinder(pole, {0, 0, 0}, 0.06f, 8.0f, 8);
  const auto poleMesh = b.addMesh(std::move(pole));
  Scene& scene = b.scene();
  for (int i = 0; i < counts.flags; ++i) {
    const int line = static_cast<int>(hash2(i, 30, 93u) * static_cast<float>(lines)) % lines;
    const float x = -half + static_cast<float>(line) * kCityBlockSize + 0.5f * kCityStreetWidth;
    const float z = (hash2(i, 31, 93u) * 2.0f - 1.0f) * half;
    const float y = cityTerrainHeight(x, z);
    b.instance(poleMesh, m.metal, placed({x, y, z}, 0.0f, 1.0f));
    const auto flag = b.addMesh(flagMesh(i));
    b.instance(flag, m.cloth, placed({x + 0.06f, y + 6.3f, z}, 0.0f, 1.0f));
    scene.animatedMeshes.push_back(flag);
    scene.animatedMotions.push_back(cityFlagMotion(i));
  }
}

}  // namespace

Scene makeCityScene(const BuiltinSceneOptions& options) {
  const CityCounts counts = cityCounts(options.cityScale);
  const CityLayout layout = cityLayout(options.cityScale);
  SceneBuilder b(options.onGeometry);
  const CityMaterials m = addCityMaterials(b, options.materialCost);
  const std::vector<Lot> lots = addGroundAndLots(b, layout, m);
  const std::vector<std::uint32_t> buildings = addBuildings(b, layout, counts, lots, m);
  addProps(b, layout, counts, m);
  addFlags(b, layout, counts, m);

  const float half = layout.halfSize;
  // The mirror: a polished wall across the far end of the main street (x = 0 runs along
  // z), facing back up the street, so the camera sees in it what is behind it.
  const float mirrorZ = half - 0.5f * kCityStreetWidth;
  Mesh wall;
  wall.name = "mirror_wall";
  appendBox(wall, {-0.3f * kCityStreetWidth, -1.0f, -0.3f}, {0.3f * kCityStreetWidth, 14.0f, 0.0f},
            UvScale{1.0f});
  b.instance(b.addMesh(std::move(wall)), m.mirror,
             placed({0.0f, cityTerrainHeight(0.0f, mirrorZ), mirrorZ}, 0.0f, 1.0f));

  Scene& scene = b.scene();
  // LODs for the buildings, most of the city's triangles, each its own BLAS. The props are
  // left whole: a shared mesh has one BLAS for all its instances, and a LOD would add a
  // second beside it rather than replace it (docs/design/culling.md, Mesh LODs).
  if (options.meshLods)
    addMeshLods(scene, buildings);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.35f, -0.8f, 0.45f));
  sun.intensity = glm::vec3(3.2f, 3.0f, 2.7f);
  scene.lights.push_back(sun);
  scene.environment.constantRadiance = glm::vec3(0.45f, 0.6f, 0.85f);
  scene.emissiveLightSampling = options.emissiveNee.value_or(true);
  const CameraPath path = makeBuiltinCameraPath("city", 1, options.cityScale, options.cityPath);
  scene.camera = path.frames.front();
  return std::move(scene);
}

gpu::VertexMotion cityFlagMotion(int flag) {
  gpu::VertexMotion motion{};
  motion.wave = glm::vec4(kFlagWidth, 6.2831853f * hash2(flag, 40, 95u), 0.0f, 0.0f);
  return motion;
}

}  // namespace memograph::runtime
