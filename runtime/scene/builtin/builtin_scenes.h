// Built-in procedural scenes for tests and benchmarks: a closed classroom-like
// room with many procedural materials and an open landscape with one expensive terrain
// material. They need no files, so the renderer can run them on the GPU machine.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

// The city's built-in camera path. `Street` (the default) flies in low from the south and
// stays in the streets at about 9 m, where the buildings around hide most of the city, as
// they do for a player in the thesis's game, so culling has something to drop. `Aerial`
// starts 150 m above the city and ends flying up and out: most of the city is on screen for
// much of it (the path docs/results.md was measured on).
enum class CityCameraPath { Street, Aerial };

// The options' ranges (parseBuiltinSceneSpec and makeBuiltinScene refuse others).
inline constexpr int kMinTerrainCells = 2, kMaxTerrainCells = 4096;
inline constexpr int kMinOctaves = 1, kMaxOctaves = 16;
// The ao and bevel options' samples: the compiler's range of the nodes' Samples
// (docs/design/traced-inputs.md), 0 for none.
inline constexpr int kMaxTracedInputSamples = 128;
inline constexpr int kMinLayers = 0, kMaxLayers = 16;

struct BuiltinSceneOptions {
  // How expensive every generated material graph is (noise octaves and extra layers); the
  // memoization benchmarks raise it until no-memo/floor matches the thesis.
  MaterialCost materialCost{};
  // Landscape terrain grid: cells per side (vertices = (cells+1)^2).
  int terrainCells = 256;
  // Light sampling of the scene's emissive triangles (Scene::emissiveLightSampling); unset:
  // the scene's own default. The classroom's is off: each lamp panel already holds a point
  // light, so on the H200 NEE of its panels and windows lowered the picture error at equal
  // samples by 3 % (mean FLIP 0.203 against 0.209) but cost 24 ms a frame on the free-material
  // floor (89.5 against 65.4 ms) and 58 ms on the memoized frame (201 against 143 ms): at
  // equal time it loses (docs/design/path-tracer.md, Light sampling).
  std::optional<bool> emissiveNee;
  // The city's size, in (0, 1]: the counts of buildings (unique meshes), props (instances)
  // and flags (animated meshes) scale together, and the street grid with them.
  double cityScale = 1.0;
  // The city's default camera (the first frame of its path) and the path `memograph bench`
  // follows.
  CityCameraPath cityPath = CityCameraPath::Street;
  // The city's buildings get mesh LODs (Scene::meshLods), which only a culled render with
  // --mesh-lods on shows (CullingOptions::showsMeshLods): built only then, since they cost
  // the full city about 6 s of one core and their geometry's upload.
  bool meshLods = false;
  // Called after each mesh the scene adds, with the vertices and triangles of all its meshes
  // so far; it may throw to stop the build. The render and bench commands pass the device's
  // buffer check (checkGeometryBuffers), so that a scene the device cannot hold is refused
  // once its geometry passes the device's limits, not after all of it is made.
  std::function<void(std::uint64_t vertices, std::uint64_t triangles)> onGeometry;
};

// "classroom", "landscape".
std::vector<std::string> builtinSceneNames();

// A built-in scene named on a command line: `NAME[:KEY=VALUE[,KEY=VALUE…]]`, keys
// `octaves`, `layers` (MaterialCost), `terrain` (terrainCells), `nee` (0 or 1:
// emissiveNee), `scale` (a number in (0, 1]: cityScale) and `path` (street or aerial:
// cityPath), e.g. `classroom:octaves=10,layers=3` or `city:scale=0.05,path=aerial`. The
// CLI strips its own `builtin:` prefix first.
struct BuiltinSceneSpec {
  std::string name;
  BuiltinSceneOptions options;
};
// Returns nothing and sets `error` (naming the bad part, the valid keys, or the option's
// meaning and range) on a syntax error or a value out of range; the name is checked by
// makeBuiltinScene.
std::optional<BuiltinSceneSpec> parseBuiltinSceneSpec(std::string_view text, std::string& error);

// Builds a built-in scene. Throws std::invalid_argument for an unknown name, the message
// listing the known ones; also for options out of range (terrainCells < 2, octaves < 1 or
// > 16, layers < 0 or > 16).
Scene makeBuiltinScene(std::string_view name, const BuiltinSceneOptions& options = {});

// The individual generators.
Scene makeClassroomScene(const BuiltinSceneOptions& options);
Scene makeLandscapeScene(const BuiltinSceneOptions& options);
Scene makeCityScene(const BuiltinSceneOptions& options);

// The landscape's terrain height (metres) at world (x, z): the same function the terrain
// mesh samples, so camera paths and object placement can follow the ground.
float landscapeTerrainHeight(float x, float z);

// The classroom's interior (metres): x ∈ [0, width], y ∈ [0, height], z ∈ [0, depth].
struct ClassroomExtent {
  float width = 9.0f;
  float height = 3.2f;
  float depth = 7.5f;
};
inline constexpr ClassroomExtent kClassroom{};

// The landscape terrain covers [-halfSize, halfSize]² in x and z.
inline constexpr float kLandscapeHalfSize = 200.0f;

// The city: square blocks of kCityBlockSize metres, street centre to street centre, with
// streets kCityStreetWidth wide; the main street runs along z at x = 0 and ends at the
// mirror wall (z = halfSize - kCityStreetWidth / 2, facing -z).
inline constexpr float kCityBlockSize = 100.0f;
inline constexpr float kCityStreetWidth = 20.0f;
struct CityCounts {
  int buildings = 0;  // each its own mesh (BLAS)
  int props = 0;      // instances of the shared prop meshes
  int flags = 0;      // animated: each its own mesh, deformed every frame
};
// Throws std::invalid_argument unless 0 < scale <= 1.
CityCounts cityCounts(double scale);
// The city covers [-halfSize, halfSize]² (plus 100 m of ground around it).
float cityHalfSize(double scale);
// The ground height (metres) at world (x, z).
float cityTerrainHeight(float x, float z);
// How flag `flag`'s cloth moves (Scene::animatedMotions, which lists the flags in order): a
// wave along the cloth (mesh space: rest.x is the distance from the pole) with the flag's
// own phase (gpu::vertexMotionOffset).
gpu::VertexMotion cityFlagMotion(int flag);

}  // namespace memograph::runtime
