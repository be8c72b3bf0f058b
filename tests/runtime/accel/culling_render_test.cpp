// Culled renders of the small city (builtin:city:scale=0.02) on lavapipe (seeds/001 §3.3):
// the per-frame figures add up in every mode, LiPaC settles on a static camera and renders
// the same picture twice, what only the mirror shows is kept by LiPaC and lost by frustum
// culling, and the BLAS cache's budgets (memory, triangles built a frame) change when BLASes
// are built, never the picture. Free materials (the floor) wherever the materials do not
// matter, so the pipeline compiles in a second instead of half a minute.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_support.h"
#include "runtime/accel/scene_culling.h"
#include "runtime/renderer.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"

namespace memograph::runtime {
namespace {

constexpr double kScale = 0.02;

// With its buildings' LODs, which the tests' culling options show or not.
Scene smallCity() {
  BuiltinSceneOptions options;
  options.cityScale = kScale;
  options.meshLods = true;
  return makeBuiltinScene("city", options);
}

// The first camera of the built-in (street) path in the main street's far half facing the
// mirror at its end (the frames CityScene.ThePathLooksAtTheMirrorFromTheStreet counts).
Camera mirrorCamera() {
  const CameraPath path = makeBuiltinCameraPath("city", 300, kScale);
  for (const Camera& c : path.frames) {
    const glm::vec3 view = glm::normalize(c.target - c.position);
    if (std::abs(c.position.x) < 0.5f * kCityStreetWidth && c.position.z > 0.0f && view.z > 0.9f &&
        c.position.y < cityTerrainHeight(c.position.x, c.position.z) + 14.0f)
      return c;
  }
  ADD_FAILURE() << "no camera of the path faces the mirror";
  return path.frames.front();
}

RendererOptions options(CullingMode mode, bool freeMaterials) {
  RendererOptions o =
      testing::testOptions(freeMaterials ? Backend::RayQuery : Backend::RayTracingPipeline);
  o.nodeLibraryDirectory.clear();  // the city's graphs need the real node library
  o.floorMaterials = freeMaterials;
  o.culling.mode = mode;
  return o;
}

RenderSettings settings(std::uint32_t frames, std::vector<Camera> path = {}) {
  RenderSettings s;
  s.width = 64;
  s.height = 36;
  s.pathsPerPixel = 1;
  s.raysPerPath = 2;  // a camera ray, and what it sees in the mirror
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

bool sameImage(const HdrImage& a, const HdrImage& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

TEST(CulledRender, TheFiguresAddUpInEveryMode) {
  const Scene scene = smallCity();
  const auto n = static_cast<std::uint32_t>(scene.instances.size());
  const Camera camera = mirrorCamera();
  std::uint64_t unculledBlasBytes = 0;
  for (CullingMode mode : {CullingMode::None, CullingMode::Frustum, CullingMode::Lipac}) {
    SCOPED_TRACE(std::string(cullingModeName(mode)));
    const RenderResult r = render(options(mode, true), scene, settings(3, {camera}));
    ASSERT_EQ(r.stats.frames.size(), 3u);
    EXPECT_EQ(r.stats.culling, cullingModeName(mode));
    for (const FrameStats& f : r.stats.frames) {
      EXPECT_EQ(f.activeInstances + f.waitingInstances + f.omittedInstances + f.inactiveInstances,
                n);
      EXPECT_EQ(f.tlasRecords,
                f.activeInstances + f.omittedInstances + f.hitboxes - f.activeHitboxes);
      EXPECT_GT(f.blasBytes, 0u);
      EXPECT_GT(f.tlasBytes, 0u);
      EXPECT_GT(f.rays, 0u);
    }
    const FrameStats& first = r.stats.frames.front();
    if (mode == CullingMode::None) {
      EXPECT_EQ(first.activeInstances, n);
      unculledBlasBytes = first.blasBytes;
    } else {
      // In the street facing the mirror most of the city is out of view. LiPaC's first look
      // activates the shared props of the hitboxes in view (one BLAS for many), so what it
      // saves shows in the BLAS bytes, not in the count.
      if (mode == CullingMode::Frustum) {
        EXPECT_LT(first.activeInstances, n / 2);
      }
      EXPECT_LT(first.blasBytes, unculledBlasBytes / 2);
      EXPECT_GT(first.blasBuilds, 0u);
      EXPECT_EQ(r.instanceStates.size(), n);
    }
    if (mode == CullingMode::Lipac) {
      EXPECT_GT(first.hitboxes, 0u);
    }
  }
}

// The trace adds an invocation's feedback counts up before it writes them (path_tracer.glsl,
// a two-slot buffer); its own tally of the counts it made must equal what the counters hold,
// on both backends and with sampled feedback, or counts were dropped on the way.
// Every frame counts here (--feedback-every 1), with every block and path, 1 block in 4, and
// 1 path in 3 (--feedback-paths 1: each counted ray weighted 3).
TEST(CulledRender, EveryFeedbackCountTheTraceMadeArrives) {
  const Scene scene = smallCity();
  const Camera camera = mirrorCamera();
  struct Sampling {
    std::uint32_t stride, paths;
  };
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    for (const Sampling sampling : {Sampling{1, 0}, Sampling{4, 0}, Sampling{1, 1}}) {
      SCOPED_TRACE(std::string(backendName(backend)) + ", feedback stride " +
                   std::to_string(sampling.stride) + ", paths " + std::to_string(sampling.paths));
      RendererOptions o = options(CullingMode::Lipac, true);
      o.context.backend = backend;
      o.culling.feedbackEvery = 1;
      o.culling.feedbackStride = sampling.stride;
      o.culling.feedbackPaths = sampling.paths;
      RenderSettings s = settings(4, {camera});
      s.pathsPerPixel = 3;  // runs of rays that count the same instance: the camera rays
      const std::uint32_t weight = sampling.stride * (sampling.paths ? 3 : 1);
      const RenderResult r = render(o, scene, s);
      ASSERT_EQ(r.stats.frames.size(), 4u);
      for (std::size_t f = 1; f < r.stats.frames.size(); ++f) {
        const FrameStats& frame = r.stats.frames[f];
        EXPECT_GT(frame.feedbackCounts, 0u) << "frame " << f;
        // A ray counts one instance and at most one box, each weighted by the sampling.
        EXPECT_LE(frame.feedbackCounts, 2u * weight * r.stats.frames[f - 1].rays) << "frame " << f;
        EXPECT_EQ(frame.feedbackCountsArrived, frame.feedbackCounts) << "frame " << f;
      }
    }
  }
}

// Three own-mesh spheres, all omitted by the first look (each a counting box, seeds/001
// §3.3.2), and a ground wider than two hitboxes, never culled. The camera at the origin looks
// down -z at a near sphere (2 wide, 10 away) that hides a far one (2 wide, 30 away): every
// camera ray through the far box crosses the near box first. A third sphere stands beside
// and behind the camera, out of view. In instance order {beside, far, near} the boxes' TLAS
// records are the same order, and lavapipe's TLAS builder pairs records by order (a tree
// over {beside, far}, then near), so the pair's bounds hold the camera: a traversal that
// stops at the first box it finds meets the far box first.
Scene twoBoxesOnOneSegment() {
  Scene scene;
  MaterialRef material;
  material.name = "Grey";
  material.graphText = testing::constantGraph("Grey", glm::vec3(0.5f), 1.0f);
  scene.materials.push_back(material);
  auto sphereAt = [&](glm::vec3 centre, float radius) {
    scene.meshes.push_back(testing::sphere(8));  // a mesh of its own: omitted first
    glm::mat4 m = glm::scale(glm::translate(glm::mat4(1.0f), centre), glm::vec3(radius));
    scene.instances.push_back({static_cast<std::uint32_t>(scene.meshes.size() - 1), 0, m});
  };
  sphereAt({5.5f, 0.0f, 1.0f}, 0.5f);    // 0: beside and behind the camera
  sphereAt({0.0f, 0.0f, -30.0f}, 1.0f);  // 1: far, behind the near one
  sphereAt({0.0f, 0.0f, -10.0f}, 1.0f);  // 2: near
  scene.meshes.push_back(testing::quad(400.0f));
  scene.instances.push_back(
      {3, 0, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -5.0f, -20.0f))});
  scene.environment.constantRadiance = glm::vec3(1.0f);
  scene.camera.position = {0.0f, 0.0f, 0.0f};
  scene.camera.target = {0.0f, 0.0f, -1.0f};
  scene.camera.verticalFovDegrees = 30.0f;
  return scene;
}

// A probe counts the nearest counting box on its segment (§3.3.2: the hitboxes' closest-hit
// shader registers the hit), on both backends: the first look's camera rays through the far
// sphere's box count the near one, so the near sphere is activated and the far one, which no
// ray reaches first, stays omitted. Counting the first box found instead activated both here.
TEST(CulledRender, TheProbeCountsTheNearestCountingBoxOnItsSegment) {
  const Scene scene = twoBoxesOnOneSegment();
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    SCOPED_TRACE(std::string(backendName(backend)));
    RendererOptions o = testing::testOptions(backend);  // the test nodes: the grey graph's
    o.floorMaterials = true;
    o.culling.mode = CullingMode::Lipac;
    o.culling.hitboxSize = 100.0f;  // one hitbox, which the look activates
    RenderSettings s = settings(1, {scene.camera});
    s.raysPerPath = 1;  // camera rays alone
    const RenderResult r = render(o, scene, s);
    ASSERT_EQ(r.stats.frames.size(), 1u);
    EXPECT_EQ(r.stats.frames[0].looks, 1u);
    EXPECT_EQ(r.stats.frames[0].hitboxes, 1u);
    ASSERT_EQ(r.instanceStates.size(), 4u);
    EXPECT_EQ(r.instanceStates[2], InstanceState::Active) << "the near sphere: its box counted";
    EXPECT_EQ(r.instanceStates[1], InstanceState::Omitted) << "the far sphere: behind it";
    EXPECT_EQ(r.instanceStates[0], InstanceState::Omitted) << "beside: out of view";
    EXPECT_EQ(r.instanceStates[3], InstanceState::Active) << "the ground is never culled";
  }
}

// On the pipeline backend a counting frame whose paths do not all count (one path in three)
// traces the others with the pipeline built without the feedback, then the counted one with
// it: two dispatches, which share the descriptor set and the shared primary ray; a frame with
// every path counting, or a quiet frame, is one. Either way every count the raygen tallied
// after its trace arrives in the counters. The first frame's counts are its look's.
TEST(CulledRender, ThePipelineBackendsCountingDispatchesCountWhatTheyTally) {
  const Scene scene = smallCity();
  struct Sampling {
    std::uint32_t every, paths;
    bool split;  // and the shared primary ray, which the counting dispatch counts
  };
  for (const Sampling sampling : {Sampling{1, 0, false}, Sampling{2, 1, true}}) {
    SCOPED_TRACE("feedback every " + std::to_string(sampling.every) + ", paths " +
                 std::to_string(sampling.paths) +
                 (sampling.split ? ", split, shared primary ray" : ""));
    RendererOptions o = options(CullingMode::Lipac, true);
    o.context.backend = Backend::RayTracingPipeline;
    o.culling.feedbackEvery = sampling.every;
    o.culling.feedbackPaths = sampling.paths;
    RenderSettings s = settings(5, {mirrorCamera()});
    s.pathsPerPixel = 3;
    s.sharedPrimaryRay = sampling.split;
    const RenderResult r = render(o, scene, s);
    ASSERT_EQ(r.stats.frames.size(), 5u);
    std::uint64_t counted = 0;
    std::uint32_t countingFrames = 0;
    for (std::size_t f = 0; f < r.stats.frames.size(); ++f) {
      const FrameStats& frame = r.stats.frames[f];
      EXPECT_EQ(frame.feedbackCountsArrived, frame.feedbackCounts) << "frame " << f;
      EXPECT_EQ(frame.traceDispatches, sampling.split ? 1u + frame.feedbackFrame : 1u)
          << "frame " << f;
      counted += frame.feedbackCountsArrived;
      countingFrames += frame.feedbackFrame;
    }
    std::printf("pipeline backend: %llu counts over %zu frames, %u of them counting\n",
                static_cast<unsigned long long>(counted), r.stats.frames.size(), countingFrames);
    EXPECT_GT(counted, 0u);
    EXPECT_EQ(countingFrames, sampling.every == 1 ? 5u : 3u);
  }
}

// LiPaC counts after the trace, which a ray query can do as well as a raygen: --backend auto
// keeps the query backend under LiPaC, and its counts arrive there.
TEST(CulledRender, LipacOnTheAutoBackendCountsWithRayQueries) {
  RendererOptions o = options(CullingMode::Lipac, true);
  o.context.backend = Backend::Auto;
  o.culling.feedbackEvery = 1;
  const RenderResult r = render(o, smallCity(), settings(2, {mirrorCamera()}));
  EXPECT_EQ(r.stats.backend, "query");
  ASSERT_EQ(r.stats.frames.size(), 2u);
  EXPECT_GT(r.stats.frames[1].feedbackCounts, 0u);
  EXPECT_EQ(r.stats.frames[1].feedbackCountsArrived, r.stats.frames[1].feedbackCounts);
}

// One path in P counting, weighted P, keeps the counters' expected value: over the frames of
// a static camera the counts add up to about what every path's do (each frame counts other
// paths), and a weight left out (P / N never applied) would give a third of them.
TEST(CulledRender, SampledPathsKeepTheCountsExpectedValue) {
  const Scene scene = smallCity();
  auto totalCounts = [&](std::uint32_t paths) {
    RendererOptions o = options(CullingMode::Lipac, true);
    o.culling.feedbackEvery = 1;
    o.culling.feedbackStride = 1;
    o.culling.feedbackPaths = paths;
    RenderSettings s = settings(7, {mirrorCamera()});
    s.pathsPerPixel = 3;
    const RenderResult r = render(o, scene, s);
    double total = 0.0;
    for (std::size_t f = 1; f < r.stats.frames.size(); ++f)
      total += double(r.stats.frames[f].feedbackCountsArrived);
    return total;
  };
  const double every = totalCounts(0), oneInThree = totalCounts(1);
  std::printf("counts over 6 frames: %.0f with one path of 3 counting, %.0f with every path\n",
              oneInThree, every);
  ASSERT_GT(every, 0.0);
  EXPECT_NEAR(oneInThree / every, 1.0, 0.1) << oneInThree << " against " << every;
}

// A counting frame with one path of P counting traces the P - 1 that do not with the
// pipeline built without the feedback, then the counted one with it, each dispatch adding its
// share of the pixels' mean; with --dispatch-paths 1 every path is a dispatch of its own, the
// counted one with the feedback. The same paths either way, so the same counts, states and
// rays (the shared primary ray once more a dispatch), and the picture up to float rounding.
// Both backends (the pipeline's raygen and the query's compute shader), and with the shared
// primary ray, whose material outputs the first path of each dispatch evaluates.
TEST(CulledRender, SplitCountingFramesTraceWhatEveryPathAloneTraces) {
  const Scene scene = smallCity();
  for (const Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    for (const bool sharedPrimary : {false, true}) {
      SCOPED_TRACE(std::string(backend == Backend::RayQuery ? "query" : "pipeline") +
                   (sharedPrimary ? ", shared primary ray" : ""));
      RenderSettings s = settings(6, {mirrorCamera()});
      s.pathsPerPixel = 4;
      s.sharedPrimaryRay = sharedPrimary;
      RendererOptions o = options(CullingMode::Lipac, true);
      o.context.backend = backend;
      o.culling.feedbackEvery = 2;
      o.pathsPerDispatch = 0;
      const RenderResult split = render(o, scene, s);
      o.pathsPerDispatch = 1;
      const RenderResult alone = render(o, scene, s);
      EXPECT_EQ(alone.instanceStates, split.instanceStates);
      ASSERT_EQ(alone.stats.frames.size(), split.stats.frames.size());
      std::uint32_t countingFrames = 0;
      for (std::size_t f = 0; f < split.stats.frames.size(); ++f) {
        const FrameStats& a = split.stats.frames[f];
        const FrameStats& b = alone.stats.frames[f];
        ASSERT_EQ(b.feedbackFrame, a.feedbackFrame);
        countingFrames += a.feedbackFrame;
        EXPECT_EQ(a.traceDispatches, 1u + a.feedbackFrame) << "frame " << f;
        EXPECT_EQ(b.traceDispatches, 4u) << "frame " << f;
        // The shared primary ray is traced by each dispatch.
        const std::uint64_t again =
            sharedPrimary
                ? std::uint64_t(b.traceDispatches - a.traceDispatches) * s.width * s.height
                : 0u;
        EXPECT_EQ(b.rays, a.rays + again) << "frame " << f;
        EXPECT_EQ(b.feedbackCountsArrived, a.feedbackCountsArrived) << "frame " << f;
      }
      EXPECT_EQ(countingFrames, 3u);
      const testing::RoundingDifference d = testing::roundingDifference(alone.image, split.image);
      std::printf("split dispatch: largest difference %.3g against a mean of %.3g\n", d.largest,
                  d.referenceMean);
      // Rounding only: a path's share lost or counted twice would move pixels by a quarter.
      ASSERT_GT(d.referenceMean, 0.0);
      EXPECT_LT(d.largest, 1e-4 * d.referenceMean);
    }
  }
}

TEST(CulledRender, FeedbackPathsThatDoNotDivideThePathsAreRefused) {
  RendererOptions o = options(CullingMode::Lipac, true);
  o.culling.feedbackPaths = 2;
  RenderSettings s = settings(1, {mirrorCamera()});
  s.pathsPerPixel = 3;
  try {
    render(o, smallCity(), s);
    FAIL() << "--feedback-paths 2 of 3 paths was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--feedback-paths 2 must divide"), std::string::npos)
        << e.what();
  }
}

// On a static camera LiPaC settles: with the defaults (every 4th frame counts, one path of
// each pixel's P, waiting 2 counting frames before leaving), with every ray of every frame
// counted, with sampled blocks (feedbackStride 4: at 64x36 only 10 of the 40 blocks of 8x8
// pixels count a frame, so an instance's count swings with the blocks sampled, far more than
// at 1080p's 32,400), and with those on every 4th frame only (--low-frames counts counting
// frames). The earlier settings wait 8 counting frames, as they did as the defaults, and run
// 32 counting frames; the defaults wait 2, so their doubling waits (2, 4, 8, 16, 32) reach
// further: they run 64 (measured on lavapipe: a hitbox still leaves for 2 counting frames at
// the 27th of 32, at the 4th wait of 16). Each checks the last 16 counting frames.
// Mesh LODs are on (their choice must settle too) but for sampled blocks counted every frame: there
// a LOD switch moves the few hits of instances at their thresholds' margin, and 9 states changed in
// the last 16 counting frames with LODs against 7 without (the bound, the states' own, is 8).
struct FeedbackSampling {
  const char* name;
  std::uint32_t stride, every, lowFrames, paths, counted;  // paths: P, feedbackPaths of them count
  bool meshLods = true;
};
const CullingOptions kDefaults{};
class LipacSettles : public ::testing::TestWithParam<FeedbackSampling> {};

TEST_P(LipacSettles, OnAStaticCameraAndRepeatsItsPicture) {
  const Scene scene = smallCity();
  // Counted frames: the feedback's frames, so that every setting gets as many updates.
  const std::uint32_t frames = GetParam().counted * GetParam().every,
                      settling = frames - 16 * GetParam().every;
  RenderSettings s = settings(frames, {mirrorCamera()});
  s.pathsPerPixel = GetParam().paths;
  RendererOptions o = options(CullingMode::Lipac, true);
  o.culling.feedbackStride = GetParam().stride;
  o.culling.feedbackEvery = GetParam().every;
  o.culling.lowFrames = GetParam().lowFrames;
  o.culling.meshLods = GetParam().meshLods;
  const RenderResult a = render(o, scene, s);
  ASSERT_EQ(a.stats.frames.size(), frames);
  // Hitboxes hold still in the last 16 counting frames; instances at the margin of their thresholds
  // may still switch, but each waits twice as long every time it leaves, so nothing cycles.
  // (Measured on lavapipe at the street path's mirror camera, 89 m from the mirror, σ_a = 4
  // and every ray counted: 511 state changes in the first 16 frames, the hitboxes still from
  // frame 11 on, 3 changes in the last 16. Run on to 64 frames, one hitbox leaves at frame 37
  // and is back at 38, 36 changes, and after that only single instances switch, 4 in 25
  // frames. With σ_a = 8: 321 and 3 changes at stride 1, 393 and 5 at stride 4.)
  std::uint32_t early = 0, late = 0;
  const std::uint32_t settledHitboxes = a.stats.frames.back().activeHitboxes;
  for (const FrameStats& f : a.stats.frames) {
    if (f.frame < settling) {
      early += f.instanceStateChanges;
      continue;
    }
    late += f.instanceStateChanges;
    EXPECT_EQ(f.activeHitboxes, settledHitboxes) << "frame " << f.frame;
  }
  std::printf(
      "stride %u, every %u frames, low %u: %u changes in the first %u frames, %u in the "
      "last %u\n",
      GetParam().stride, GetParam().every, GetParam().lowFrames, early, settling, late,
      frames - settling);
  EXPECT_GT(early, 0u) << "the feedback activated nothing";
  EXPECT_LE(late, GetParam().stride == 1 ? 4u : 8u)
      << "states still change in the last " << frames - settling << " frames (" << early
      << " changes in the first " << settling << ")";
  const RenderResult b = render(o, scene, s);
  EXPECT_TRUE(sameImage(a.image, b.image)) << "same seed, same device: the same picture";
  EXPECT_EQ(a.instanceStates, b.instanceStates);
}

INSTANTIATE_TEST_SUITE_P(
    CulledRender, LipacSettles,
    ::testing::Values(FeedbackSampling{"TheDefaultsAtTwoPaths", kDefaults.feedbackStride,
                                       kDefaults.feedbackEvery, kDefaults.lowFrames, 2, 64},
                      FeedbackSampling{"FeedbackStride1Every1", 1, 1, 8, 1, 32},
                      FeedbackSampling{"FeedbackStride4Every1", 4, 1, 8, 1, 32, false},
                      FeedbackSampling{"FeedbackStride4Every4", 4, 4, 8, 1, 32}),
    [](const ::testing::TestParamInfo<FeedbackSampling>& info) {
      return std::string(info.param.name);
    });

// Instances behind the camera, past frustum culling's radius, in the line of the main street
// (what the mirror at its end shows).
std::vector<std::uint32_t> behindInTheStreet(const Scene& scene, const Camera& camera,
                                             float radius) {
  const std::vector<Bounds> bounds = instanceBounds(scene);
  const glm::vec3 view = glm::normalize(camera.target - camera.position);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < bounds.size(); ++i) {
    const glm::vec3 c = bounds[i].centre();
    const glm::vec3 d = c - camera.position;
    if (glm::dot(d, view) < -radius && std::abs(c.x) < 1.5f * kCityStreetWidth &&
        glm::length(d) > radius)
      out.push_back(i);
  }
  return out;
}

// How many of `instances` a render left active.
std::uint32_t activeAmong(const RenderResult& r, const std::vector<std::uint32_t>& instances) {
  std::uint32_t active = 0;
  for (std::uint32_t i : instances)
    active += r.instanceStates[i] == InstanceState::Active;
  return active;
}

TEST(CulledRender, WhatOnlyTheMirrorShowsIsKeptByLipacAndLostByFrustumCulling) {
  const Scene scene = smallCity();
  const Camera camera = mirrorCamera();
  const RenderSettings s = settings(6, {camera});
  const RenderResult lipac = render(options(CullingMode::Lipac, false), scene, s);
  // Frustum culling is geometry alone: free materials, so its pipeline compiles in a second.
  const RenderResult frustum = render(options(CullingMode::Frustum, true), scene, s);
  const std::vector<std::uint32_t> behind =
      behindInTheStreet(scene, camera, CullingOptions{}.radius);
  ASSERT_FALSE(behind.empty());
  EXPECT_GT(activeAmong(lipac, behind), 0u) << "of " << behind.size() << " instances behind";
  EXPECT_EQ(activeAmong(frustum, behind), 0u);
}

// Mean absolute difference over every channel of two images of one size.
double meanDifference(const HdrImage& a, const HdrImage& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    sum += std::abs(double(a.rgba[i]) - double(b.rgba[i]));
  return sum / double(a.rgba.size());
}

// LiPaC's first look: flying in from south of the city (the path's first camera), the first
// frame holds what a probe trace of its camera reaches, not every instance in its frustum:
// fewer BLAS bytes here than frustum culling's (24.4 against 42.0 MB at the defaults; 29.9
// while the probe counted the first counting box it found, not the nearest), with the picture
// kept. The probe counts every ray whatever the
// feedback stride (with 1 in 4 blocks counted the picture missed this test's bound: 1.14 % of the
// image's mean, against 0.78 % when every ray counted).
TEST(CulledRender, TheFirstLookHoldsWhatTheFirstCameraReaches) {
  const Scene scene = smallCity();
  const Camera approach = makeBuiltinCameraPath("city", 300, kScale).frames.front();
  const RenderSettings s = settings(1, {approach});
  RendererOptions o = options(CullingMode::Lipac, true);
  // The look's bound, without the mesh LODs' own difference (at 64 x 36 a pixel is metres
  // wide and the buildings take their coarsest levels: 1.02 % of the mean with them;
  // MeshLodRender checks their picture).
  o.culling.meshLods = false;
  const RenderResult withFirstLook = render(o, scene, s);
  RendererOptions frustum = options(CullingMode::Frustum, true);
  frustum.culling.meshLods = false;
  const RenderResult without = render(frustum, scene, s);
  const RenderResult unculled = render(options(CullingMode::None, true), scene, s);
  const FrameStats& a = withFirstLook.stats.frames.front();
  const FrameStats& b = without.stats.frames.front();
  EXPECT_LT(a.blasBytes, b.blasBytes);
  // The look is counted, and its probe's GPU time is part of the frame's.
  EXPECT_EQ(a.looks, 1u);
  EXPECT_EQ(b.looks, 0u);
  EXPECT_GT(a.lookMilliseconds, 0.0);
  EXPECT_GT(a.gpuMilliseconds, a.lookMilliseconds);
  // Its image is not kept, so its paths trace no shadow rays: at most the path's rays a pixel
  // (the frame, which lights its hits, traces more).
  const std::uint64_t pathRays = std::uint64_t(s.width) * s.height * s.raysPerPath;
  EXPECT_GE(a.lookRays, std::uint64_t(s.width) * s.height) << "a camera ray a pixel at least";
  EXPECT_LE(a.lookRays, pathRays);
  EXPECT_GT(a.rays, pathRays) << "the frame's shadow rays";
  // The probe registers the nearest box a ray crosses, so an instance seen only past another's
  // box waits a frame: a few pixels at 64x36 and one path, a mean difference of 0.009-0.094 %
  // of the image's mean over seeds 0-5, 0.009 % at this test's seed 0 (0.11-0.95 % and
  // 0.27 % while the probe counted the first box it found, which could be a farther one;
  // 0.62-0.78 % when the look still traced shadow rays, whose random numbers sent its paths
  // elsewhere; 0.01-0.03 % without the first look). A building lost from view would cost
  // several %. At 192x108, P = 4, L = 3 its mean LDR-FLIP against unculled was 0.0009 against
  // 0.0061 without.
  HdrImage black = unculled.image;
  std::fill(black.rgba.begin(), black.rgba.end(), 0.0f);
  const double share =
      meanDifference(withFirstLook.image, unculled.image) / meanDifference(unculled.image, black);
  std::printf(
      "first look: %.3f %% of the image's mean from unculled; BLAS %.1f against %.1f MB; "
      "%llu rays in the look, %llu in the frame\n",
      100.0 * share, a.blasBytes / 1e6, b.blasBytes / 1e6, (unsigned long long)a.lookRays,
      (unsigned long long)a.rays);
  EXPECT_LT(share, 0.01);
  EXPECT_GT(a.omittedInstances, 0u) << "what the probe's rays did not reach waits as a box";
}

// A look after the render's first is sparse (FrameLoop::look): turning from the open country
// south of the city to the city, the second frame's look traces one path per 2x2 pixels, on
// both backends (the pipeline's raygen launched over the whole frame traced rays outside the
// frustum until its launch took the look's size). Its frame holds fewer BLAS bytes than
// activating all that the turn brings into view (the look's purpose), with the picture kept:
// 0.074 % of the image's mean from unculled, where the full look's was 0.089 % and
// activating everything 0.028 %. One of its rays activates what it reaches: with the frames'
// minimum of two rays the picture was 0.80 % off.
TEST(CulledRender, ASparseLookHoldsWhatATurnBringsIntoView) {
  const Scene scene = smallCity();
  const Camera approach = makeBuiltinCameraPath("city", 300, kScale).frames.front();
  Camera away = approach;
  away.target = 2.0f * approach.position - approach.target;
  const RenderSettings s = settings(2, {away, approach});
  const RenderResult unculled = render(options(CullingMode::None, true), scene, s);
  HdrImage black = unculled.image;
  std::fill(black.rgba.begin(), black.rgba.end(), 0.0f);
  const double mean = meanDifference(unculled.image, black);
  for (const Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    SCOPED_TRACE(backend == Backend::RayQuery ? "ray queries" : "ray-tracing pipeline");
    RendererOptions o = options(CullingMode::Lipac, true);
    o.context.backend = backend;
    o.culling.meshLods = false;
    const RenderResult turned = render(o, scene, s);
    RendererOptions unlooked = o;
    unlooked.culling.lookAppearing = 1000000;  // only the first frame looks
    const RenderResult withoutLook = render(unlooked, scene, s);
    ASSERT_EQ(turned.stats.frames.size(), 2u);
    const FrameStats& turn = turned.stats.frames[1];
    EXPECT_EQ(turn.looks, 1u);
    EXPECT_EQ(withoutLook.stats.frames[1].looks, 0u);
    EXPECT_LT(turn.blasBytes, withoutLook.stats.frames[1].blasBytes);
    // A camera ray per 2x2 block at least, and no more than the path's rays for each.
    const std::uint64_t blocks = std::uint64_t((s.width + 1) / 2) * ((s.height + 1) / 2);
    EXPECT_GE(turn.lookRays, blocks);
    EXPECT_LE(turn.lookRays, blocks * s.raysPerPath);
    const double share = meanDifference(turned.image, unculled.image) / mean;
    std::printf(
        "turn: %.3f %% of the image's mean from unculled; BLAS %.1f against %.1f MB "
        "without the look; %llu rays in the look\n",
        100.0 * share, turn.blasBytes / 1e6, withoutLook.stats.frames[1].blasBytes / 1e6,
        (unsigned long long)turn.lookRays);
    EXPECT_LT(share, 0.003);
  }
}

// Sampled feedback (1 in 4 pixel blocks a frame, weighted 4) still finds what only the
// mirror shows: the instances behind the camera can only be activated by counted rays.
TEST(CulledRender, SampledFeedbackStillKeepsWhatOnlyTheMirrorShows) {
  const Scene scene = smallCity();
  const Camera camera = mirrorCamera();
  RendererOptions o = options(CullingMode::Lipac, false);
  o.culling.feedbackStride = 4;
  const RenderResult lipac = render(o, scene, settings(8, {camera}));
  const std::vector<std::uint32_t> behind =
      behindInTheStreet(scene, camera, CullingOptions{}.radius);
  EXPECT_GT(activeAmong(lipac, behind), 0u) << "of " << behind.size() << " instances behind";
}

// --feedback-every 4: frames 0, 4, 8, ... trace with the feedback, the others with the
// pipeline built without it: after a counting frame the counts its trace tallied all
// arrived, after a quiet one its trace tallied none (it fails when the quiet frames trace
// with the feedback's pipeline). With a quarter of the frames counting, what only the mirror
// shows is still found, and the picture repeats, on both backends.
TEST(CulledRender, FeedbackEveryKthFrameCountsThoseFramesOnly) {
  const Scene scene = smallCity();
  const Camera camera = mirrorCamera();
  const std::vector<std::uint32_t> behind =
      behindInTheStreet(scene, camera, CullingOptions{}.radius);
  for (Backend backend : {Backend::RayQuery, Backend::RayTracingPipeline}) {
    SCOPED_TRACE(backendName(backend));
    RendererOptions o = options(CullingMode::Lipac, true);
    o.context.backend = backend;
    o.culling.feedbackEvery = 4;
    const RenderSettings s = settings(24, {camera});
    const RenderResult r = render(o, scene, s);
    ASSERT_EQ(r.stats.frames.size(), 24u);
    for (std::size_t f = 0; f < r.stats.frames.size(); ++f)
      EXPECT_EQ(r.stats.frames[f].feedbackFrame, f % 4 == 0 ? 1u : 0u) << "frame " << f;
    for (std::size_t f = 1; f < r.stats.frames.size(); ++f) {
      const FrameStats& frame = r.stats.frames[f];
      if ((f - 1) % 4 == 0) {
        EXPECT_GT(frame.feedbackCounts, 0u) << "frame " << f << " follows a counting frame";
        EXPECT_EQ(frame.feedbackCountsArrived, frame.feedbackCounts) << "frame " << f;
      } else {
        EXPECT_EQ(frame.feedbackCounts, 0u) << "frame " << f << " follows a quiet frame";
        EXPECT_EQ(frame.feedbackCountsArrived, 0u) << "frame " << f;
      }
    }
    EXPECT_GT(activeAmong(r, behind), 0u) << "of " << behind.size() << " instances behind";
    const RenderResult again = render(o, scene, s);
    EXPECT_TRUE(sameImage(r.image, again.image)) << "same seed, same device: the same picture";
  }
}

// The host writes each frame's TLAS records from the instance states: under LiPaC the active
// instances and the boxes of omitted instances and inactive hitboxes; without culling (the
// city's animated flags keep the TLAS dynamic) every instance whose BLAS is built, on cameras far
// apart so that states change. The records follow the states alone: a second render gives the same
// picture bit for bit, the same states and the same record counts.
TEST(CulledRender, TheHostFillWritesTheRecordsTheStatesKeep) {
  const Scene scene = smallCity();
  const auto n = static_cast<std::uint32_t>(scene.instances.size());
  const CameraPath path = makeBuiltinCameraPath("city", 300, kScale);
  const std::vector<Camera> cameras = {path.frames[0], path.frames[120], mirrorCamera(),
                                       mirrorCamera(), mirrorCamera()};
  for (CullingMode mode : {CullingMode::Lipac, CullingMode::None}) {
    const RenderResult a = render(options(mode, true), scene, settings(5, cameras));
    const RenderResult b = render(options(mode, true), scene, settings(5, cameras));
    EXPECT_TRUE(sameImage(a.image, b.image)) << cullingModeName(mode);
    EXPECT_EQ(a.instanceStates, b.instanceStates) << cullingModeName(mode);
    ASSERT_EQ(a.stats.frames.size(), b.stats.frames.size());
    for (std::size_t f = 0; f < a.stats.frames.size(); ++f) {
      const FrameStats& frame = a.stats.frames[f];
      EXPECT_EQ(frame.tlasRecords, b.stats.frames[f].tlasRecords)
          << cullingModeName(mode) << " frame " << f;
      EXPECT_EQ(frame.tlasRecords, frame.activeInstances + frame.omittedInstances + frame.hitboxes -
                                       frame.activeHitboxes)
          << cullingModeName(mode) << " frame " << f;
      if (mode == CullingMode::None) {
        EXPECT_EQ(frame.activeInstances + frame.waitingInstances, n) << "frame " << f;
      }
    }
  }
}

// Five cameras far apart on the path, then the mirror camera (which sees a small part of
// the city) for two frames.
std::vector<Camera> spreadPath() {
  const CameraPath path = makeBuiltinCameraPath("city", 300, kScale);
  std::vector<Camera> out;
  for (int f : {0, 60, 120, 180, 240})
    out.push_back(path.frames[std::size_t(f)]);
  out.push_back(mirrorCamera());
  out.push_back(mirrorCamera());
  return out;
}

TEST(CulledRender, TheBlasCacheEvictsUnderASmallBudgetWithTheSamePicture) {
  const Scene scene = smallCity();
  const RenderSettings s = settings(7, spreadPath());
  RendererOptions keepAll = options(CullingMode::Frustum, true);
  keepAll.culling.blasKeepFrames = 0;  // only the budget evicts
  const RenderResult unlimited = render(keepAll, scene, s);
  RendererOptions small = keepAll;
  small.culling.blasBudgetBytes = 1u << 20;
  const RenderResult budgeted = render(small, scene, s);
  std::uint32_t evictions = 0, builds = 0, unlimitedBuilds = 0;
  for (const FrameStats& f : budgeted.stats.frames) {
    evictions += f.blasEvictions;
    builds += f.blasBuilds;
  }
  for (const FrameStats& f : unlimited.stats.frames) {
    EXPECT_EQ(f.blasEvictions, 0u);
    unlimitedBuilds += f.blasBuilds;
  }
  EXPECT_GT(evictions, 0u);
  EXPECT_GT(builds, unlimitedBuilds) << "evicted BLASes are built again when needed";
  EXPECT_LT(budgeted.stats.frames.back().blasBytes, unlimited.stats.frames.back().blasBytes);
  EXPECT_TRUE(sameImage(budgeted.image, unlimited.image));
}

TEST(CulledRender, BlasesUnusedForKeepFramesAreEvicted) {
  const Scene scene = smallCity();
  RendererOptions o = options(CullingMode::Frustum, true);
  o.culling.blasKeepFrames = 2;
  // The path's cameras far apart (each frame keeps another part of the city), then four
  // frames at the mirror camera.
  std::vector<Camera> path = spreadPath();
  path.insert(path.end(), 2, mirrorCamera());
  const RenderResult r = render(o, scene, settings(9, path));
  std::uint32_t evictions = 0;
  for (const FrameStats& f : r.stats.frames)
    evictions += f.blasEvictions;
  EXPECT_GT(evictions, 0u);
  const RenderResult fresh = render(o, scene, settings(1, {mirrorCamera()}));
  EXPECT_EQ(r.stats.frames.back().blasBytes, fresh.stats.frames.front().blasBytes)
      << "after more than 2 frames at the mirror camera only its BLASes are resident";
}

// With mesh LODs (the default) the LODs' BLASes come under the same budget; without them the
// whole meshes need ten times the triangles.
TEST(CulledRender, TheBuildBudgetSpreadsBuildsOverFrames) {
  const Scene scene = smallCity();
  for (const bool meshLods : {true, false}) {
    RendererOptions o = options(CullingMode::Frustum, true);
    o.culling.meshLods = meshLods;
    o.culling.blasBuildTriangles = meshLods ? 2000 : 20000;
    // 16 frames: with the parts a level removes counted, the LODs the camera needs are finer
    // (more triangles), and at 2,000 a frame one instance still waited in the 12th.
    const RenderResult r = render(o, scene, settings(16, {mirrorCamera()}));
    const FrameStats& first = r.stats.frames.front();
    EXPECT_GT(first.waitingInstances, 0u) << "LODs " << meshLods;
    EXPECT_GT(first.blasBuilds, 0u);
    EXPECT_EQ(r.stats.frames.back().waitingInstances, 0u) << "every needed BLAS came in time";
    RendererOptions unlimited = options(CullingMode::Frustum, true);
    unlimited.culling.meshLods = meshLods;
    const RenderResult all = render(unlimited, scene, settings(1, {mirrorCamera()}));
    EXPECT_EQ(r.stats.frames.back().activeInstances, all.stats.frames.front().activeInstances);
    EXPECT_EQ(r.instanceLods, all.instanceLods) << "the same LODs once all have come";
  }
}

// --blas-build-ms: a budget below any build's time builds one BLAS a frame (the first frame's
// first alone, to time it), one too large for any builds all at once, as without a budget;
// either way the frame holds the same instances once every BLAS has come. The extremes
// are used so that what is built when does not depend on this machine's speed.
TEST(CulledRender, TheBuildTimeBudgetSpreadsBuildsOverFrames) {
  const Scene scene = smallCity();
  RendererOptions o = options(CullingMode::Frustum, true);
  // No flag's BLAS is rebuilt within the frames (those builds count too).
  o.culling.blasRebuildEvery = 1024;
  const RenderResult unlimited = render(o, scene, settings(1, {mirrorCamera()}));
  const std::uint32_t needed = unlimited.stats.frames.front().blasBuilds;
  ASSERT_GT(needed, 3u);

  o.culling.blasBuildMilliseconds = 1e6;
  const RenderResult ample = render(o, scene, settings(1, {mirrorCamera()}));
  EXPECT_EQ(ample.stats.frames.front().blasBuilds, needed) << "the first alone, then the rest";
  EXPECT_EQ(ample.stats.frames.front().waitingInstances, 0u);

  o.culling.blasBuildMilliseconds = 1e-9;
  const RenderResult tight = render(o, scene, settings(needed + 1, {mirrorCamera()}));
  std::uint32_t built = 0;
  for (const FrameStats& f : tight.stats.frames) {
    EXPECT_LE(f.blasBuilds, 1u) << "frame " << f.frame;
    built += f.blasBuilds;
  }
  EXPECT_GT(tight.stats.frames.front().waitingInstances, 0u);
  EXPECT_EQ(built, needed);
  EXPECT_EQ(tight.stats.frames.back().waitingInstances, 0u) << "every needed BLAS came";
  EXPECT_EQ(tight.stats.frames.back().activeInstances,
            unlimited.stats.frames.front().activeInstances);
}

}  // namespace
}  // namespace memograph::runtime

namespace memograph::runtime {
namespace {

// A dark quad facing a camera under a white sky, animated to slide sideways by `speed`
// units a second; without culling, so the animation alone makes the TLAS dynamic.
Scene slidingQuad(float speed) {
  Scene scene;
  Mesh quad = testing::quad(2.0f);
  scene.meshes.push_back(quad);
  MaterialRef material;
  material.name = "Dark";
  material.graphText = testing::constantGraph("Dark", glm::vec3(0.05f), 1.0f);
  scene.materials.push_back(material);
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.animatedMeshes = {0};
  gpu::VertexMotion slide{};
  slide.drift = glm::vec4(speed, 0.0f, 0.0f, 0.0f);
  scene.animatedMotions = {slide};
  scene.environment.constantRadiance = glm::vec3(1.0f);
  scene.camera.position = {0.0f, 3.0f, 0.01f};
  scene.camera.target = {0.0f, 0.0f, 0.0f};
  scene.camera.verticalFovDegrees = 30.0f;
  return scene;
}

// Frames at one camera, the last at a camera moved by a hair so that the image is that
// frame alone (accumulation restarts when the camera moves).
RenderSettings lastFrameAlone(const Scene& scene, std::uint32_t frames) {
  RenderSettings s;
  s.width = s.height = 16;
  s.pathsPerPixel = 2;
  s.raysPerPath = 2;
  s.frames = frames;
  s.secondsPerFrame = 0.25f;
  s.cameraPath.assign(frames - 1, scene.camera);
  Camera moved = scene.camera;
  moved.position.z += 1e-4f;
  s.cameraPath.push_back(moved);
  return s;
}

TEST(AnimatedBlases, AMovedMeshIsHitWhereItIsNow) {
  // At 2 units a second, frame 4 (t = 1 s) has the 2-unit quad beside the view's centre.
  const Scene scene = slidingQuad(2.0f);
  RendererOptions o = testing::testOptions(Backend::RayQuery);
  const RenderResult still = render(o, slidingQuad(0.0f), lastFrameAlone(scene, 5));
  const RenderResult moved = render(o, scene, lastFrameAlone(scene, 5));
  const double centreStill = testing::meanChannel(still.image, 0, 6, 6, 10, 10);
  const double centreMoved = testing::meanChannel(moved.image, 0, 6, 6, 10, 10);
  EXPECT_LT(centreStill, 0.2) << "the quad covers the centre at rest";
  EXPECT_GT(centreMoved, 0.9) << "the sky shows where the quad was";
  std::uint32_t updates = 0, builds = 0;
  for (const FrameStats& f : moved.stats.frames) {
    updates += f.blasUpdates;
    builds += f.blasBuilds;
  }
  EXPECT_EQ(updates, 5u) << "one in-place update a frame";
  EXPECT_EQ(builds, 0u) << "the quad, the only mesh, is never rebuilt within 16 frames";
}

TEST(AnimatedBlases, UpdatedInPlaceGivesTheRebuiltPicture) {
  const Scene scene = slidingQuad(0.3f);
  RendererOptions updated = testing::testOptions(Backend::RayQuery);
  RendererOptions rebuilt = updated;
  rebuilt.culling.blasRebuildEvery = 1;
  const RenderSettings s = lastFrameAlone(scene, 6);
  const RenderResult a = render(updated, scene, s);
  const RenderResult b = render(rebuilt, scene, s);
  std::uint32_t aUpdates = 0, bUpdates = 0, bBuilds = 0;
  for (const FrameStats& f : a.stats.frames)
    aUpdates += f.blasUpdates;
  for (const FrameStats& f : b.stats.frames) {
    bUpdates += f.blasUpdates;
    bBuilds += f.blasBuilds;
  }
  EXPECT_EQ(aUpdates, 6u);
  EXPECT_EQ(bUpdates, 0u);
  EXPECT_EQ(bBuilds, 6u);
  EXPECT_TRUE(sameImage(a.image, b.image));
}

}  // namespace
}  // namespace memograph::runtime
