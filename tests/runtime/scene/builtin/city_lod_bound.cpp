// The share of the city's triangles that the LOD choice keeps when every instance stays in the
// TLAS and takes the level its distance alone allows (a pixel's width there, the render's
// height): `scenes_city_lod_bound [scale] [height] [pixel-error]` (defaults 1, 1080, 1), along
// both camera paths (360 cameras each), with the run time's own choice given no feedback. With
// feedback it is never coarser (ray cones only narrow the footprint), so where culling removes
// little, as from the air, this bounds what LiPaC with mesh LODs can reach; triangles stand for
// BLAS bytes. Printed for the choice's error (the simplifier's, or the longest part a level removes
// whole, whichever is larger) and for the simplifier's alone.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "runtime/accel/lod_choice.h"
#include "runtime/accel/scene_culling.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"

namespace {

using namespace memograph::runtime;

double triangles(const Mesh& mesh) {
  return double(mesh.indices.size() / 3);
}

struct KeptShare {
  double peak = 0.0, mean = 0.0;
  // Over the cameras more than kHighAbove m up (the aerial path's flight over the city),
  // where culling removes little: the smallest and largest share (low > high: none).
  double low = 1e30, high = -1e30;
};
constexpr float kHighAbove = 100.0f;

// Per camera of `path`, the run time's choice (InstanceLodChoice) without feedback: the
// triangles of the distinct (mesh, level) pairs the instances show (a BLAS per mesh LOD,
// shared), over those of every mesh whole.
KeptShare keptShare(const Scene& scene, const std::vector<Bounds>& bounds, const CameraPath& path,
                    std::uint32_t height, float pixelError) {
  std::set<std::uint32_t> meshes;
  for (const Instance& instance : scene.instances)
    meshes.insert(instance.mesh);
  double whole = 0.0;
  for (const std::uint32_t m : meshes)
    whole += triangles(scene.meshes[m]);
  InstanceLodChoice choice(scene, bounds, pixelError);
  KeptShare share;
  double sum = 0.0;
  for (const Camera& camera : path.frames) {
    choice.update(camera, pixelSpreadAngle(camera, height), {});
    std::set<std::pair<std::uint32_t, std::uint32_t>> shown;
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
      shown.insert({scene.instances[i].mesh, choice.wanted()[i]});
    double kept = 0.0;
    for (const auto& [mesh, level] : shown)
      kept += triangles(level == 0 ? scene.meshes[mesh] : scene.meshLods[mesh][level - 1].mesh);
    share.peak = std::max(share.peak, kept / whole);
    sum += kept / whole;
    if (camera.position.y > kHighAbove) {
      share.low = std::min(share.low, kept / whole);
      share.high = std::max(share.high, kept / whole);
    }
  }
  share.mean = sum / double(path.frames.size());
  return share;
}

}  // namespace

int main(int argc, char** argv) {
  double scale = 1.0;
  int height = 1080;
  float pixelError = 1.0f;
  try {
    if (argc > 1)
      scale = std::stod(argv[1]);
    if (argc > 2)
      height = std::stoi(argv[2]);
    if (argc > 3)
      pixelError = std::stof(argv[3]);
  } catch (const std::exception&) {
    height = 0;
  }
  if (argc > 4 || !(scale > 0.0 && scale <= 1.0) || height < 1 || !(pixelError > 0.0f)) {
    std::cerr << "usage: scenes_city_lod_bound [scale in (0, 1]] [height >= 1] "
                 "[pixel-error > 0]\n";
    return 2;
  }
  BuiltinSceneOptions options;
  options.cityScale = scale;
  options.meshLods = true;
  const Scene scene = makeCityScene(options);
  // The same scene with no level's removed parts counted: the simplifier's error alone.
  Scene surfaceOnly = scene;
  for (std::vector<MeshLod>& lods : surfaceOnly.meshLods)
    for (MeshLod& lod : lods)
      lod.removedPart = 0.0f;
  const std::vector<Bounds> bounds = instanceBounds(scene);
  std::printf(
      "city scale %g, %d rows, --lod-pixel-error %g: triangles kept, peak (mean) over "
      "the path\n",
      scale, height, pixelError);
  for (const CityCameraPath which : {CityCameraPath::Street, CityCameraPath::Aerial}) {
    const CameraPath path = makeBuiltinCameraPath("city", 360, scale, which);
    const KeptShare counted = keptShare(scene, bounds, path, height, pixelError);
    const KeptShare surface = keptShare(surfaceOnly, bounds, path, height, pixelError);
    std::printf(
        "  %s: %.3f (%.3f) with removed parts counted, %.3f (%.3f) the surface's "
        "error alone\n",
        which == CityCameraPath::Aerial ? "aerial" : "street", counted.peak, counted.mean,
        surface.peak, surface.mean);
    if (counted.low <= counted.high)
      std::printf(
          "    above %.0f m: %.3f-%.3f with removed parts counted, %.3f-%.3f the "
          "surface's error alone\n",
          kHighAbove, counted.low, counted.high, surface.low, surface.high);
  }
  return 0;
}
