// Mesh LODs in culled renders on lavapipe (seeds/001 §3.1.1, §3.3.1; docs/design/culling.md, "Mesh
// LODs"): BLASes are shared per (mesh, LOD); what a curved mirror magnifies keeps its finest
// level though its distance alone would take the coarsest, and the wavefront chooses as the
// megakernel does there; on the small city's paths the peak AS memory falls with LODs.
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/accel/lod_choice.h"
#include "runtime/accel/scene_culling.h"
#include "runtime/renderer.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/builtin/mesh_lods.h"
#include "runtime/scene/scene_upload.h"

namespace memograph::runtime {
namespace {

constexpr double kScale = 0.02;

// A 30 x 26 m wall of 10 x 8 windows (six boxes each, as the city's): a mesh whose LODs thin
// its frames.
Mesh windowedWall() {
  Mesh mesh;
  mesh.name = "wall";
  appendBox(mesh, {-15.0f, 0.0f, -0.5f}, {15.0f, 26.0f, 0.0f});
  for (int floor = 0; floor < 8; ++floor)
    for (int w = 0; w < 10; ++w) {
      const float x = -13.5f + 3.0f * float(w), y = 0.8f + 3.2f * float(floor);
      appendBox(mesh, {x - 0.75f, y - 0.12f, 0.0f}, {x + 0.75f, y, 0.23f});
      appendBox(mesh, {x - 0.7f, y + 1.68f, 0.0f}, {x + 0.7f, y + 1.8f, 0.18f});
      appendBox(mesh, {x - 0.7f, y, 0.0f}, {x - 0.58f, y + 1.68f, 0.18f});
      appendBox(mesh, {x + 0.58f, y, 0.0f}, {x + 0.7f, y + 1.68f, 0.18f});
      appendBox(mesh, {x - 0.06f, y, 0.0f}, {x + 0.06f, y + 1.68f, 0.11f});
      appendBox(mesh, {x - 0.58f, y, -0.12f}, {x + 0.58f, y + 1.68f, -0.08f});
    }
  return mesh;
}

RendererOptions lodOptions(CullingMode mode, bool meshLods, bool freeMaterials) {
  RendererOptions o =
      testing::testOptions(freeMaterials ? Backend::RayQuery : Backend::RayTracingPipeline);
  o.nodeLibraryDirectory.clear();  // the built-in graphs need the real node library
  o.floorMaterials = freeMaterials;
  o.culling.mode = mode;
  o.culling.meshLods = meshLods;
  return o;
}

RenderSettings tiny(std::uint32_t frames, std::vector<Camera> path = {}) {
  RenderSettings s;
  s.width = 64;
  s.height = 36;
  s.pathsPerPixel = 1;
  s.raysPerPath = 2;  // a camera ray, and what it sees in a mirror
  s.frames = frames;
  s.cameraPath = std::move(path);
  return s;
}

RenderResult render(const RendererOptions& o, const Scene& scene, const RenderSettings& s) {
  Renderer renderer(o);
  RenderResult result = renderer.render(scene, s);
  EXPECT_TRUE(renderer.context().validationErrors().empty())
      << renderer.context().validationErrors().front();
  return result;
}

// Four instances of the wall facing the camera, two near (3 m) and two far (400 m), all in
// its frustum: frustum culling keeps them all, each pair at its own LOD.
TEST(MeshLodRender, BlasesAreSharedPerMeshLod) {
  Scene scene;
  scene.meshes.push_back(windowedWall());
  addMeshLods(scene, {0});
  ASSERT_GE(scene.meshLods[0].size(), 2u);
  scene.materials.push_back({"Grey", "", testing::constantGraph("Grey", glm::vec3(0.5f), 0.5f)});
  const auto at = [](float x, float z) { return glm::translate(glm::mat4(1.0f), {x, -13.0f, z}); };
  scene.instances = {{0, 0, at(-16.0f, -3.0f)},
                     {0, 0, at(16.0f, -3.0f)},
                     {0, 0, at(-40.0f, -400.0f)},
                     {0, 0, at(40.0f, -400.0f)}};
  scene.camera.position = glm::vec3(0.0f);
  scene.camera.target = {0.0f, 0.0f, -1.0f};
  scene.camera.verticalFovDegrees = 60.0f;
  scene.environment.constantRadiance = glm::vec3(1.0f);
  RendererOptions o = testing::testOptions(Backend::RayQuery);
  o.culling.mode = CullingMode::Frustum;
  o.culling.meshLods = true;
  const RenderResult lods = render(o, scene, tiny(1));
  o.culling.meshLods = false;
  const RenderResult whole = render(o, scene, tiny(1));

  ASSERT_EQ(lods.instanceLods.size(), 4u);
  const std::vector<std::uint8_t>& level = lods.instanceLods;
  std::printf("LODs near %u %u, far %u %u\n", level[0], level[1], level[2], level[3]);
  EXPECT_EQ(level[0], level[1]);
  EXPECT_EQ(level[2], level[3]);
  EXPECT_LT(level[0], level[2]) << "the far pair coarser";
  // One BLAS per (mesh, LOD): two builds for four instances; one without LODs.
  EXPECT_EQ(lods.stats.frames.front().activeInstances, 4u);
  EXPECT_EQ(lods.stats.frames.front().blasBuilds, 2u);
  EXPECT_EQ(whole.stats.frames.front().blasBuilds, 1u);
  EXPECT_TRUE(whole.instanceLods.empty());
}

// A concave spherical mirror (radius 20, so its focus is 10 m out) and the camera 11 m from
// it, looking into it: the cones it reflects converge (eq. 2.12's curvature spread) towards a
// point about 130 m out, where the wall stands behind the camera. Its distance's pixel at
// 64 x 36 is over 2 m, which takes the wall's coarsest LOD; the cones that reach it are a few
// centimetres wide, so LiPaC's footprint feedback keeps it at its finest.
Mesh concaveMirror(glm::vec3 centre, float radius, float halfAngleDegrees, int cells) {
  Mesh mesh;
  mesh.name = "concave_mirror";
  const float t = std::tan(glm::radians(halfAngleDegrees));
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const float u = (2.0f * float(i) / float(cells) - 1.0f) * t;
      const float v = (2.0f * float(j) / float(cells) - 1.0f) * t;
      const glm::vec3 d = glm::normalize(glm::vec3(u, v, 1.0f));
      mesh.positions.push_back(centre + radius * d);
      mesh.normals.push_back(-d);  // towards the centre: the side the camera sees
    }
  const auto row = static_cast<std::uint32_t>(cells + 1);
  for (std::uint32_t j = 0; j < std::uint32_t(cells); ++j)
    for (std::uint32_t i = 0; i < std::uint32_t(cells); ++i) {
      const std::uint32_t a = j * row + i;
      mesh.indices.insert(mesh.indices.end(), {a, a + row, a + 1, a + 1, a + row, a + row + 1});
    }
  return mesh;
}

// The mirror and the wall behind the camera, and the camera looking into the mirror.
struct MirroredWall {
  Scene scene;
  Camera camera;
};

MirroredWall mirroredWall() {
  MirroredWall m;
  Scene& scene = m.scene;
  const glm::vec3 centre{0.0f, 5.0f, 0.0f};
  scene.meshes.push_back(concaveMirror(centre, 20.0f, 20.0f, 24));
  scene.meshes.push_back(windowedWall());
  addMeshLods(scene, {1});
  scene.materials.push_back({"Mirror", "", mirrorGraph("Mirror")});
  // The wall's windows face the mirror (+z) 130 m out from it (z = 20 - 130), centred on its
  // axis (y = 5).
  const glm::mat4 wallPlace = glm::translate(glm::mat4(1.0f), {0.0f, -8.0f, -110.0f});
  scene.instances = {{0, 0, glm::mat4(1.0f)}, {1, 0, wallPlace}};
  m.camera.position = {0.0f, 5.0f, 9.0f};
  m.camera.target = {0.0f, 5.0f, 20.0f};
  m.camera.verticalFovDegrees = 40.0f;
  scene.camera = m.camera;
  scene.environment.constantRadiance = glm::vec3(0.5f, 0.6f, 0.8f);
  return m;
}

RenderResult renderMirroredWall(const MirroredWall& m, Shading shading) {
  RendererOptions o = lodOptions(CullingMode::Lipac, true, false);
  o.shading = shading;
  o.culling.feedbackEvery = 1;  // the wall comes in a few frames: hitbox, box, instance
  return render(o, m.scene, tiny(8, {m.camera}));
}

TEST(MeshLodRender, WhatACurvedMirrorMagnifiesKeepsItsFinestLod) {
  const MirroredWall m = mirroredWall();
  ASSERT_GE(m.scene.meshLods[1].size(), 2u);
  const RenderResult r = renderMirroredWall(m, Shading::Megakernel);
  ASSERT_EQ(r.instanceStates.size(), 2u);
  ASSERT_EQ(r.instanceStates[1], InstanceState::Active) << "the mirror shows the wall";
  ASSERT_EQ(r.instanceLods.size(), 2u);
  EXPECT_EQ(r.instanceLods[1], 0u) << "the magnified wall keeps its finest LOD";

  // Distance alone, at the same camera and pixel, would take the wall's coarsest level.
  InstanceLodChoice byDistance(m.scene, instanceBounds(m.scene), CullingOptions{}.lodPixelError);
  byDistance.update(m.camera, pixelSpreadAngle(m.camera, tiny(1).height), {});
  EXPECT_EQ(byDistance.wanted()[1], m.scene.meshLods[1].size());
}

// The wavefront's trace pass writes the same footprints (the cone its path state carries,
// at the hit), so it chooses the megakernel's LODs: the magnified wall keeps its finest level
// there too, where without footprints its distance would take the coarsest.
TEST(MeshLodRender, TheWavefrontChoosesTheMegakernelsLodsForAMirroredWall) {
  const MirroredWall m = mirroredWall();
  const RenderResult megakernel = renderMirroredWall(m, Shading::Megakernel);
  const RenderResult wavefront = renderMirroredWall(m, Shading::Wavefront);
  EXPECT_EQ(wavefront.stats.shading, "wavefront");
  ASSERT_EQ(wavefront.instanceStates.size(), 2u);
  ASSERT_EQ(wavefront.instanceStates[1], InstanceState::Active) << "the mirror shows the wall";
  ASSERT_EQ(wavefront.instanceLods.size(), 2u);
  EXPECT_EQ(wavefront.instanceLods[1], 0u) << "the magnified wall keeps its finest LOD";
  EXPECT_EQ(wavefront.instanceLods, megakernel.instanceLods);
}

// The small city's street path (its first 12 cameras, flying in) and its aerial path (the
// first 12: from above), LiPaC with and without LODs: the peak AS bytes fall with LODs.
TEST(MeshLodRender, LodsLowerLipacsPeakAsMemoryOnTheSmallCitysPaths) {
  for (const CityCameraPath which : {CityCameraPath::Street, CityCameraPath::Aerial}) {
    BuiltinSceneOptions sceneOptions;
    sceneOptions.cityScale = kScale;
    sceneOptions.cityPath = which;
    sceneOptions.meshLods = true;
    const Scene scene = makeBuiltinScene("city", sceneOptions);
    const CameraPath path = makeBuiltinCameraPath("city", 300, kScale, which);
    const std::vector<Camera> cameras(path.frames.begin(), path.frames.begin() + 12);
    const RenderSettings s = tiny(12, cameras);
    const RenderResult lods = render(lodOptions(CullingMode::Lipac, true, true), scene, s);
    const RenderResult whole = render(lodOptions(CullingMode::Lipac, false, true), scene, s);
    const auto peak = [](const RenderResult& r) {
      std::uint64_t bytes = 0;
      for (const FrameStats& f : r.stats.frames)
        bytes = std::max(bytes, f.blasBytes + f.tlasBytes);
      return bytes;
    };
    std::printf("%s path: peak AS %.2f MB with LODs, %.2f MB without (%.2fx)\n",
                which == CityCameraPath::Street ? "street" : "aerial", peak(lods) / 1e6,
                peak(whole) / 1e6, double(peak(lods)) / double(peak(whole)));
    EXPECT_LT(peak(lods), peak(whole));
  }
}

// Bad LODs in a scene are named before anything is uploaded, never a device fault.
TEST(MeshLodScene, BrokenLodsAreNamed) {
  const auto message = [](const Scene& scene) {
    try {
      validateScene(scene);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Scene scene = testing::greyQuadScene();
  scene.meshLods.resize(scene.meshes.size());
  scene.meshLods[0].push_back({testing::quad(2.0f), 0.1f});
  EXPECT_EQ(message(scene), "accepted");

  Scene wrongCount = scene;
  wrongCount.meshLods.emplace_back();
  EXPECT_NE(message(wrongCount).find("mesh LOD lists"), std::string::npos);
  Scene pastVertices = scene;
  pastVertices.meshLods[0][0].mesh.indices[1] = 99;
  EXPECT_NE(message(pastVertices).find("LOD 1: index 1 is 99"), std::string::npos)
      << message(pastVertices);
  Scene finerError = scene;
  finerError.meshLods[0].push_back({testing::quad(2.0f), 0.05f});
  EXPECT_NE(message(finerError).find("LOD 2: error"), std::string::npos);
  Scene nanError = scene;
  nanError.meshLods[0][0].error = std::nanf("");
  EXPECT_NE(message(nanError).find("LOD 1: error"), std::string::npos);
  Scene animated = scene;
  animated.animatedMeshes = {0};
  EXPECT_NE(message(animated).find("is animated and has LODs"), std::string::npos);
  Scene tooMany = scene;
  tooMany.meshLods[0].assign(kMaxMeshLods + 1, {testing::quad(2.0f), 0.1f});
  EXPECT_NE(message(tooMany).find("LODs; at most"), std::string::npos);
}

}  // namespace
}  // namespace memograph::runtime
