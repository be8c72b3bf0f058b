// Parameterized recipes that generate the built-in scenes' material graphs (.mgraph text):
// wood, painted metal, plastic, fabric, tiles, plaster, … Each reads only the UV input, so
// the compiler marks it cacheable (thesis §4.2), and each spends most of its time in
// multi-octave noise, so that memoization has something to save (the memoization
// benchmarks need the no-memo/floor ratio of the thesis's Classroom scene).
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace memograph::runtime {

// The cost knob of every recipe. `octaves` is the Detail of each noise node; `layers` adds
// that many extra detail-noise layers mixed into the base colour (each one a full
// multi-octave noise evaluation that cannot be pruned). `ambientOcclusionSamples` and
// `bevelSamples` (0: none) put an Ambient Occlusion node on the base colour and a Bevel node
// on the normal (MaterialBuilder), whose rays the path tracer traces from every hit (traced
// inputs, docs/design/traced-inputs.md).
struct MaterialCost {
  int octaves = 6;
  int layers = 1;
  int ambientOcclusionSamples = 0;
  int bevelSamples = 0;
};

// Where in UV space a recipe's pattern sits: two materials from one recipe with different
// seeds look different (offset pattern), not just differently tinted.
struct RecipeSeed {
  std::uint32_t value = 0;
  glm::vec2 offset() const;
};

struct WoodParams {
  glm::vec3 light{0.62f, 0.42f, 0.24f};
  glm::vec3 dark{0.33f, 0.19f, 0.09f};
  float ringFrequency = 9.0f;  // rings across one noise feature
  float grainStretch = 8.0f;   // grain is this much finer across than along u
  float roughness = 0.45f;
};
struct PaintedMetalParams {
  glm::vec3 paint{0.2f, 0.35f, 0.6f};
  glm::vec3 metal{0.6f, 0.6f, 0.62f};
  float wear = 0.25f;  // share of the surface where paint is worn off
};
struct PlasticParams {
  glm::vec3 color{0.8f, 0.2f, 0.1f};
  float roughness = 0.35f;
  float speckle = 0.15f;
};
struct FabricParams {
  glm::vec3 warp{0.3f, 0.3f, 0.5f};
  glm::vec3 weft{0.2f, 0.2f, 0.35f};
  float threadsPerMetre = 120.0f;
};
struct TileParams {
  glm::vec3 tileA{0.75f, 0.74f, 0.7f};
  glm::vec3 tileB{0.35f, 0.36f, 0.38f};
  glm::vec3 grout{0.5f, 0.5f, 0.48f};
  float tileSize = 0.3f;  // metres
  bool checker = true;    // alternate A/B; else A with brick offset rows
};
struct PlasterParams {
  glm::vec3 color{0.85f, 0.83f, 0.78f};
  float roughness = 0.85f;
};
struct ChalkboardParams {
  glm::vec3 board{0.08f, 0.17f, 0.12f};
  glm::vec3 chalk{0.75f, 0.78f, 0.76f};
};
struct LeatherParams {
  glm::vec3 color{0.4f, 0.1f, 0.08f};
  float roughness = 0.55f;
};
struct PosterParams {
  glm::vec3 a{0.9f, 0.6f, 0.1f};
  glm::vec3 b{0.1f, 0.4f, 0.7f};
  glm::vec3 paper{0.92f, 0.9f, 0.84f};
  float cellsPerMetre = 6.0f;
};
struct CorkParams {
  glm::vec3 color{0.6f, 0.42f, 0.26f};
};
struct EmitterParams {
  glm::vec3 radiance{10.0f, 9.5f, 8.5f};
  glm::vec3 baseColor{0.9f, 0.9f, 0.9f};
};
struct TerrainParams {
  float metresPerUv = 8.0f;  // the terrain mesh's UV scale, so masks have sizes in metres
};
struct RockParams {
  glm::vec3 light{0.52f, 0.5f, 0.47f};
  glm::vec3 dark{0.25f, 0.24f, 0.23f};
};
struct BarkParams {
  glm::vec3 color{0.3f, 0.2f, 0.13f};
};
struct FoliageParams {
  glm::vec3 light{0.25f, 0.45f, 0.12f};
  glm::vec3 dark{0.06f, 0.2f, 0.05f};
};

// Each returns the complete .mgraph text of a material called `name` (an identifier).
std::string woodGraph(const std::string& name, const WoodParams& p, RecipeSeed seed,
                      MaterialCost cost);
std::string paintedMetalGraph(const std::string& name, const PaintedMetalParams& p, RecipeSeed seed,
                              MaterialCost cost);
std::string plasticGraph(const std::string& name, const PlasticParams& p, RecipeSeed seed,
                         MaterialCost cost);
std::string fabricGraph(const std::string& name, const FabricParams& p, RecipeSeed seed,
                        MaterialCost cost);
std::string tileGraph(const std::string& name, const TileParams& p, RecipeSeed seed,
                      MaterialCost cost);
std::string plasterGraph(const std::string& name, const PlasterParams& p, RecipeSeed seed,
                         MaterialCost cost);
std::string chalkboardGraph(const std::string& name, const ChalkboardParams& p, RecipeSeed seed,
                            MaterialCost cost);
std::string leatherGraph(const std::string& name, const LeatherParams& p, RecipeSeed seed,
                         MaterialCost cost);
std::string posterGraph(const std::string& name, const PosterParams& p, RecipeSeed seed,
                        MaterialCost cost);
std::string corkGraph(const std::string& name, const CorkParams& p, RecipeSeed seed,
                      MaterialCost cost);
// The visible stand-in for a material whose graph is missing: a magenta and black checker
// (five checks per UV unit), as renderers traditionally show missing textures.
std::string missingMaterialGraph(const std::string& name);
// Cheap on purpose: lamps and windows are light sources, not texture work.
std::string emitterGraph(const std::string& name, const EmitterParams& p);

// A polished metal mirror (metallic 1, roughness 0.02): constant, so it costs no noise.
std::string mirrorGraph(const std::string& name);
// The landscape's one expensive material: grass, dirt, rock and snow layers, each a
// multi-octave noise, blended by large-scale masks that are themselves noise over UV.
// The masks stand in for height and slope: real height/slope masks would read the
// position and normal inputs and make the terrain uncacheable.
std::string terrainGraph(const std::string& name, const TerrainParams& p, MaterialCost cost);
std::string rockGraph(const std::string& name, const RockParams& p, RecipeSeed seed,
                      MaterialCost cost);
std::string barkGraph(const std::string& name, const BarkParams& p, RecipeSeed seed,
                      MaterialCost cost);
std::string foliageGraph(const std::string& name, const FoliageParams& p, RecipeSeed seed,
                         MaterialCost cost);

}  // namespace memograph::runtime
