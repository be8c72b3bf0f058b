// SceneCulling without a device (seeds/001 §3.3.2): the frustum test, frustum culling's
// radius, and LiPaC's state machine fed made-up hit counters: hitboxes activate above ϑ_a
// and deactivate only after K frames below ϑ_d (doubling K each time, so nothing cycles, up to
// 16 K, and halving it back once it stops cycling),
// instances with their own BLAS go through "omitted" and activate above σ_a, instances that
// appear in the frustum large enough are activated at once, and bad options are refused.
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/accel/scene_culling.h"

namespace memograph::runtime {
namespace {

Mesh cube() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                 {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  m.normals.assign(8, glm::vec3(0, 1, 0));
  m.indices = {0, 1, 2};
  return m;
}

glm::mat4 at(float x, float z) {
  glm::mat4 m(1.0f);
  m[3] = glm::vec4(x, 0.0f, z, 1.0f);
  return m;
}

// Instances 0..3: a shared mesh at x = 0, 20, 200, 220 (z = 0); instance 4: a unique mesh at
// x = 210. Hitboxes of 100: {0, 20} in one, {200, 220, 210} in another.
Scene row() {
  Scene s;
  s.meshes = {cube(), cube()};
  for (float x : {0.0f, 20.0f, 200.0f, 220.0f})
    s.instances.push_back({0, 0, at(x, 0.0f)});
  s.instances.push_back({1, 0, at(210.0f, 0.0f)});
  MaterialRef material;
  material.name = "m";
  s.materials.push_back(material);
  return s;
}

// Looking along -z from far away, so nothing is large enough to be activated on appearing.
Camera farAway() {
  Camera c;
  c.position = {110.0f, 0.5f, 5000.0f};
  c.target = {110.0f, 0.5f, 0.0f};
  return c;
}

// Looking away from everything (+z).
Camera lookingAway() {
  Camera c;
  c.position = {110.0f, 0.5f, 50.0f};
  c.target = {110.0f, 0.5f, 100.0f};
  return c;
}

CullingOptions lipac() {
  CullingOptions o;
  o.mode = CullingMode::Lipac;
  o.hitboxSize = 100.0f;
  o.hitboxActivate = 20.0;  // per million rays: 20 hits of 10^6 rays
  o.hitboxDeactivate = 2.0;
  o.instanceActivate = 4.0;
  o.instanceDeactivate = 0.4;
  o.lowFrames = 3;
  o.feedbackStride = 1;  // the made-up counters are every ray's (a test below samples)
  return o;
}

constexpr std::uint64_t kRays = 1000000;

TEST(Frustum, KeepsWhatIsInFrontAndDropsWhatIsBehindOrBeside) {
  Camera c;
  c.position = {0, 0, 0};
  c.target = {0, 0, -1};
  c.verticalFovDegrees = 60.0f;
  const Frustum f = cameraFrustum(c, 1.0f);
  EXPECT_TRUE(f.intersects({{-1, -1, -11}, {1, 1, -9}}));
  EXPECT_FALSE(f.intersects({{-1, -1, 9}, {1, 1, 11}}));     // behind
  EXPECT_FALSE(f.intersects({{20, -1, -11}, {22, 1, -9}}));  // beside, past the 30° side
  EXPECT_TRUE(f.intersects({{5, -1, -11}, {7, 1, -9}}));     // inside the 30° side
  EXPECT_TRUE(f.intersects({{-100, -1, -1}, {100, 1, 1}}));  // across the camera
}

TEST(FrustumCulling, KeepsTheRadiusAroundTheCamera) {
  CullingOptions o;
  o.mode = CullingMode::Frustum;
  o.radius = 30.0f;
  SceneCulling culling(row(), o);
  Camera c = lookingAway();
  c.position = {10.0f, 0.5f, 15.0f};  // 14 from instances 0 and 1, far from the rest
  c.target = {10.0f, 0.5f, 100.0f};
  culling.update(c, 1.0f, {}, 0);
  const auto& s = culling.states();
  EXPECT_EQ(s[0], InstanceState::Active);
  EXPECT_EQ(s[1], InstanceState::Active);
  EXPECT_EQ(s[2], InstanceState::Inactive);
  EXPECT_EQ(culling.counts().active, 2u);
  EXPECT_EQ(culling.counts().inactive, 3u);
}

TEST(Lipac, HitboxesActivateAboveTheThresholdAndOwnMeshesGoThroughOmitted) {
  SceneCulling culling(row(), lipac());
  ASSERT_EQ(culling.hitboxCount(), 3u);  // x in [0, 220] at 100: three columns, one row
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t far = culling.hitboxOf(2);
  ASSERT_EQ(culling.hitboxOf(4), far);
  ASSERT_NE(culling.hitboxOf(0), far);
  culling.update(farAway(), 1.0f, {}, 0);
  EXPECT_EQ(culling.counts().active, 0u) << "nothing large enough to activate on sight";
  EXPECT_EQ(culling.counts().activeHitboxes, 0u);

  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  hits[n + far] = 19;  // below ϑ_a = 20
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_FALSE(culling.hitboxActive(far));
  hits[n + far] = 20;
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_TRUE(culling.hitboxActive(far));
  EXPECT_EQ(culling.states()[2], InstanceState::Active) << "shared mesh: active at once";
  EXPECT_EQ(culling.states()[3], InstanceState::Active);
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted) << "own mesh: a box counts first";
  EXPECT_EQ(culling.states()[0], InstanceState::Inactive);

  // The omitted instance's box counts 3 (< σ_a = 4), then 4.
  hits.assign(hits.size(), 0);
  hits[2] = hits[3] = 50;
  hits[4] = 3;
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted);
  hits[4] = 4;
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_EQ(culling.states()[4], InstanceState::Active);
}

// With sampled feedback one counted ray adds its weight (feedbackStride here): the minimum
// of 4 hits for a hitbox stays 4 rays (16 counts at stride 4), so one stray ray cannot
// switch it on.
TEST(Lipac, SampledFeedbackKeepsTheMinimumInRays) {
  CullingOptions o = lipac();
  o.feedbackStride = 4;
  SceneCulling culling(row(), o);
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t far = culling.hitboxOf(2);
  culling.update(farAway(), 1.0f, {}, 0);
  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  const std::uint64_t fewRays = 1000;  // ϑ_a stands for 0.02 hits: the minimum decides
  hits[n + far] = 12;                  // three counted rays
  culling.update(farAway(), 1.0f, hits, fewRays, o.feedbackStride);
  EXPECT_FALSE(culling.hitboxActive(far));
  hits[n + far] = 16;  // four
  culling.update(farAway(), 1.0f, hits, fewRays, o.feedbackStride);
  EXPECT_TRUE(culling.hitboxActive(far));
}

// Activates instance 0's hitbox (its box counted 100 rays of a million) and returns it.
std::uint32_t activateFirstHitbox(SceneCulling& culling) {
  const std::uint32_t h = culling.hitboxOf(0);
  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  culling.update(farAway(), 1.0f, {}, 0);
  hits[culling.instanceCount() + h] = 100;
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_TRUE(culling.hitboxActive(h));
  return h;
}

TEST(Lipac, DeactivatesOnlyAfterLowFramesAndBacksOff) {
  SceneCulling culling(row(), lipac());
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t h = activateFirstHitbox(culling);
  std::vector<std::uint32_t> hits(culling.counterCount(), 0);

  // Between ϑ_d and ϑ_a: stays, however long.
  hits.assign(hits.size(), 0);
  hits[0] = 2;
  for (int frame = 0; frame < 20; ++frame) {
    culling.update(farAway(), 1.0f, hits, kRays);
    ASSERT_TRUE(culling.hitboxActive(h)) << frame;
  }
  // Below ϑ_d: K = 3 frames.
  hits[0] = 1;
  culling.update(farAway(), 1.0f, hits, kRays);
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_TRUE(culling.hitboxActive(h));
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_FALSE(culling.hitboxActive(h));
  EXPECT_EQ(culling.states()[0], InstanceState::Inactive);

  // Its box sees many rays again: active; the next deactivation needs 2K = 6 frames.
  hits.assign(hits.size(), 0);
  hits[n + h] = 100;
  culling.update(farAway(), 1.0f, hits, kRays);
  ASSERT_TRUE(culling.hitboxActive(h));
  hits.assign(hits.size(), 0);
  for (int frame = 0; frame < 5; ++frame) {
    culling.update(farAway(), 1.0f, hits, kRays);
    ASSERT_TRUE(culling.hitboxActive(h)) << frame;
  }
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_FALSE(culling.hitboxActive(h));
}

// With --feedback-every K the updates of the frames between counting ones (no counters)
// change nothing: a hitbox leaves after `lowFrames` low counting frames, however many quiet
// ones come between.
TEST(Lipac, QuietFramesLeaveTheLowFramesAsTheyAre) {
  CullingOptions o = lipac();
  o.lowFrames = 2;
  o.feedbackEvery = 2;
  SceneCulling culling(row(), o);
  const std::uint32_t h = activateFirstHitbox(culling);
  const std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  culling.update(farAway(), 1.0f, hits, kRays);  // 1 low frame of 2
  for (int quiet = 0; quiet < 5; ++quiet) {
    culling.update(farAway(), 1.0f, {}, 0);  // no counts: no change
    ASSERT_TRUE(culling.hitboxActive(h)) << quiet;
  }
  culling.update(farAway(), 1.0f, hits, kRays);  // 2 of 2
  EXPECT_FALSE(culling.hitboxActive(h));
}

// The departure wait over hundreds of cycles (§3.3.2: deactivate "only after the number of
// hits has been low for several frames"). A hitbox whose box sees many rays while its
// instances see none, the cycle the doubling is for, waits 3, 6, 12, 24, then 48 counting
// frames (16 x --low-frames 3), never more however often it comes back. In, and straddling
// its threshold, it keeps that wait. Once it stops cycling the wait halves back after each
// run of 48 counting frames without a low one: out for 47 it still waits 48, out for 48 it
// waits 24, out for 4 x 48 it waits 3 again, and in with hits for 3 x 48 a wait of 24 is 3.
TEST(Lipac, TheHitboxDepartureWaitStaysBoundedAndDecaysBack) {
  const CullingOptions o = lipac();
  ASSERT_EQ(o.lowFrames, 3u);
  const std::uint32_t cap = 48;
  ASSERT_EQ(o.lowFrames << kDepartureWaitMaxDoublings, cap);
  SceneCulling culling(row(), o);
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t h = culling.hitboxOf(0);
  culling.update(farAway(), 1.0f, {}, 0);
  std::vector<std::uint32_t> boxHit(culling.counterCount(), 0);
  boxHit[n + h] = 100;
  std::vector<std::uint32_t> instanceHit(culling.counterCount(), 0);
  instanceHit[0] = 50;
  const std::vector<std::uint32_t> none(culling.counterCount(), 0);
  auto frames = [&](const std::vector<std::uint32_t>& hits, std::uint32_t count) {
    for (std::uint32_t f = 0; f < count; ++f)
      culling.update(farAway(), 1.0f, hits, kRays);
  };
  // Counting frames with no hits until it leaves (at most 5000, where the old doubling went
  // past 1000).
  auto framesToLeave = [&] {
    std::uint32_t count = 0;
    while (culling.hitboxActive(h) && count < 5000) {
      culling.update(farAway(), 1.0f, none, kRays);
      ++count;
    }
    return count;
  };
  auto activate = [&] {
    frames(boxHit, 1);
    EXPECT_TRUE(culling.hitboxActive(h));
  };

  std::vector<std::uint32_t> waits;
  for (int cycle = 0; cycle < 300; ++cycle) {
    activate();
    waits.push_back(framesToLeave());
  }
  EXPECT_EQ(std::vector<std::uint32_t>(waits.begin(), waits.begin() + 6),
            (std::vector<std::uint32_t>{3, 6, 12, 24, 48, 48}));
  EXPECT_EQ(*std::max_element(waits.begin(), waits.end()), cap);
  EXPECT_EQ(std::count(waits.begin(), waits.end(), cap), 296) << "at the cap from then on";

  activate();
  for (int frame = 0; frame < 100; ++frame)
    frames(frame % 2 ? instanceHit : none, 1);  // neither 48 low frames nor 48 hit in a row
  ASSERT_TRUE(culling.hitboxActive(h));
  EXPECT_EQ(framesToLeave(), cap) << "straddling its threshold does not shorten the wait";
  // The frame that activates it is out too: a run of cap - 1, then of cap.
  frames(none, cap - 2);
  activate();
  EXPECT_EQ(framesToLeave(), cap) << "one frame short of a run";
  frames(none, cap - 1);
  activate();
  EXPECT_EQ(framesToLeave(), cap / 2) << "one run: halved once";
  frames(none, 4 * cap);
  activate();
  EXPECT_EQ(framesToLeave(), 3u) << "four runs: 48 down to 3";
  activate();
  EXPECT_EQ(framesToLeave(), 6u) << "a departure still doubles it";
  activate();
  EXPECT_EQ(framesToLeave(), 12u);
  activate();
  frames(instanceHit, 3 * cap - 1);  // in, and hit: not cycling either
  ASSERT_TRUE(culling.hitboxActive(h));
  EXPECT_EQ(framesToLeave(), 3u) << "three runs: 24 down to 3";
}

// The same for an instance with its own BLAS in an active hitbox: active while its rays come,
// omitted after its wait, at most 48 counting frames over 300 cycles, and back to 3 after it
// stays omitted for 4 runs of 48 counting frames.
TEST(Lipac, TheInstanceDepartureWaitStaysBoundedAndDecaysBack) {
  SceneCulling culling(row(), lipac());
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t far = culling.hitboxOf(4);
  culling.update(farAway(), 1.0f, {}, 0);
  // The shared instances beside it keep the hitbox active; instance 4 counts σ_a or nothing.
  std::vector<std::uint32_t> reached(culling.counterCount(), 0);
  reached[2] = reached[3] = 50;
  reached[n + far] = 100;
  reached[4] = 4;
  std::vector<std::uint32_t> notReached = reached;
  notReached[n + far] = 0;
  notReached[4] = 0;
  culling.update(farAway(), 1.0f, reached, kRays);
  ASSERT_TRUE(culling.hitboxActive(far));
  ASSERT_EQ(culling.states()[4], InstanceState::Omitted);
  auto activate = [&] {
    culling.update(farAway(), 1.0f, reached, kRays);
    EXPECT_EQ(culling.states()[4], InstanceState::Active);
  };
  auto framesToLeave = [&] {
    std::uint32_t count = 0;
    while (culling.states()[4] == InstanceState::Active && count < 5000) {
      culling.update(farAway(), 1.0f, notReached, kRays);
      ++count;
    }
    EXPECT_TRUE(culling.hitboxActive(far));
    return count;
  };
  std::vector<std::uint32_t> waits;
  for (int cycle = 0; cycle < 300; ++cycle) {
    activate();
    waits.push_back(framesToLeave());
  }
  EXPECT_EQ(std::vector<std::uint32_t>(waits.begin(), waits.begin() + 6),
            (std::vector<std::uint32_t>{3, 6, 12, 24, 48, 48}));
  EXPECT_EQ(*std::max_element(waits.begin(), waits.end()), 48u);
  for (int frame = 0; frame < 4 * 48; ++frame)
    culling.update(farAway(), 1.0f, notReached, kRays);
  ASSERT_EQ(culling.states()[4], InstanceState::Omitted);
  activate();
  EXPECT_EQ(framesToLeave(), 3u);
}

TEST(Lipac, ThresholdsScaleWithTheRaysTraced) {
  SceneCulling culling(row(), lipac());
  const std::uint32_t n = culling.instanceCount();
  const std::uint32_t h = culling.hitboxOf(0);
  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  culling.update(farAway(), 1.0f, {}, 0);
  hits[n + h] = 100;  // 100 of 10^7 rays: 10 per million, below ϑ_a
  culling.update(farAway(), 1.0f, hits, 10 * kRays);
  EXPECT_FALSE(culling.hitboxActive(h));
  culling.update(farAway(), 1.0f, hits, kRays / 10);  // 1000 per million
  EXPECT_TRUE(culling.hitboxActive(h));
}

TEST(Lipac, InstancesThatAppearLargeAreActivatedAtOnce) {
  SceneCulling culling(row(), lipac());
  culling.update(lookingAway(), 1.0f, {}, 0);
  EXPECT_EQ(culling.counts().active, 0u);
  Camera c = lookingAway();
  c.target = {0.5f, 0.5f, 0.5f};  // turns to instance 0, 115 away: 1 unit is 0.4° of 45°
  CullingOptions o = lipac();
  culling.update(c, 1.0f, std::vector<std::uint32_t>(culling.counterCount(), 0), kRays);
  EXPECT_EQ(culling.states()[0], InstanceState::Inactive) << "too small to be seen at once";
  c.position = {0.5f, 0.5f, 5.0f};  // 4.5 away: about 10° of 45°
  SceneCulling near(row(), o);
  near.update(lookingAway(), 1.0f, {}, 0);
  near.update(c, 1.0f, std::vector<std::uint32_t>(near.counterCount(), 0), kRays);
  EXPECT_EQ(near.states()[0], InstanceState::Active);
}

// The first frame's look: the hitboxes in view start active (shared meshes active, own meshes as
// counting boxes), nothing counts as appearing in the first update, and there the omitted
// instances the probe's rays reached above σ_a are activated, the others stay boxes.
TEST(Lipac, ALookActivatesOnlyWhatTheProbeReached) {
  SceneCulling culling(row(), lipac());
  ASSERT_TRUE(culling.wantsLook(farAway(), 1.0f));
  culling.look(farAway(), 1.0f);
  EXPECT_FALSE(culling.wantsLook(farAway(), 1.0f)) << "nothing appears in the same view";
  for (std::uint32_t h = 0; h < culling.hitboxCount(); ++h)
    EXPECT_EQ(culling.hitboxActive(h), culling.hitboxUsed(h)) << h;
  EXPECT_EQ(culling.states()[0], InstanceState::Active) << "shared mesh";
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted) << "own mesh: a box counts";

  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  hits[0] = 50;
  culling.update(farAway(), 1.0f, hits, kRays);
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted) << "not reached: still a box";
  SceneCulling reached(row(), lipac());
  reached.look(farAway(), 1.0f);
  hits[4] = 4;  // σ_a
  reached.update(farAway(), 1.0f, hits, kRays);
  EXPECT_EQ(reached.states()[4], InstanceState::Active);

  CullingOptions frustum = lipac();
  frustum.mode = CullingMode::Frustum;
  EXPECT_FALSE(SceneCulling(row(), frustum).wantsLook(farAway(), 1.0f)) << "no probe to look";
}

// A look later on: turning to face an instance with its own BLAS, near and large, asks for
// one when at least lookAppearing such instances appear; after it the instance is a counting
// box, not activated as appearing, until the probe's rays reach it.
TEST(Lipac, TurningToFaceHiddenOwnMeshesAsksForALook) {
  CullingOptions o = lipac();
  o.lookAppearing = 1;
  SceneCulling culling(row(), o);
  culling.look(lookingAway(), 1.0f);
  culling.update(lookingAway(), 1.0f, std::vector<std::uint32_t>(culling.counterCount(), 0), kRays);
  Camera facing;
  facing.position = {210.5f, 0.5f, 5.0f};
  facing.target = {210.5f, 0.5f, 0.5f};  // instance 4, 4.5 away: large
  o.lookAppearing = 2;
  SceneCulling twoNeeded(row(), o);
  twoNeeded.look(lookingAway(), 1.0f);
  EXPECT_FALSE(twoNeeded.wantsLook(facing, 1.0f)) << "one own mesh appears, two needed";
  ASSERT_TRUE(culling.wantsLook(facing, 1.0f));
  culling.look(facing, 1.0f);
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted);
  culling.update(facing, 1.0f, std::vector<std::uint32_t>(culling.counterCount(), 0), kRays);
  EXPECT_EQ(culling.states()[4], InstanceState::Omitted) << "not activated as appearing";
  std::vector<std::uint32_t> hits(culling.counterCount(), 0);
  hits[4] = 4;
  culling.update(facing, 1.0f, hits, kRays);
  EXPECT_EQ(culling.states()[4], InstanceState::Active);
}

TEST(CullingOptions, BadValuesAreRefusedWithTheirFlag) {
  auto message = [](CullingOptions o) {
    try {
      validateCullingOptions(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CullingOptions o = lipac();
  o.hitboxDeactivate = 30.0;
  EXPECT_NE(message(o).find("--hitbox-deactivate"), std::string::npos);
  o = lipac();
  o.hitboxSize = 0.0f;
  EXPECT_NE(message(o).find("--hitbox-size"), std::string::npos);
  // The whole-number options' ranges, each end and one past it (whether --feedback-paths
  // divides the paths per pixel the renderer checks).
  struct Range {
    std::uint32_t CullingOptions::*field;
    std::uint32_t low, high;
    const char* flag;
  };
  for (const Range r : {Range{&CullingOptions::lowFrames, 1, 1024, "--low-frames"},
                        Range{&CullingOptions::blasRebuildEvery, 1, 1024, "--blas-rebuild-every"},
                        Range{&CullingOptions::blasKeepFrames, 0, 1024, "--blas-keep-frames"},
                        Range{&CullingOptions::feedbackStride, 1, 64, "--feedback-stride"},
                        Range{&CullingOptions::feedbackPaths, 0, 64, "--feedback-paths"},
                        Range{&CullingOptions::feedbackEvery, 1, 64, "--feedback-every"}}) {
    SCOPED_TRACE(r.flag);
    o = lipac();
    for (const std::uint32_t fine : {r.low, r.high}) {
      o.*r.field = fine;
      EXPECT_EQ(message(o), "");
    }
    o.*r.field = r.high + 1;
    EXPECT_EQ(message(o), std::string(r.flag) + " must be in " + std::to_string(r.low) + ".." +
                              std::to_string(r.high) + ", not " + std::to_string(r.high + 1));
    if (r.low > 0) {
      o.*r.field = r.low - 1;
      EXPECT_NE(message(o).find(r.flag), std::string::npos);
    }
  }
  // The build time budget: milliseconds in [0, 1e6] (0: none).
  for (const double fine : {0.0, 0.25, 1e6}) {
    o = lipac();
    o.blasBuildMilliseconds = fine;
    EXPECT_EQ(message(o), "") << fine;
  }
  for (const double bad : {-0.5, 1e6 * 1.01, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    o = lipac();
    o.blasBuildMilliseconds = bad;
    EXPECT_EQ(message(o), "--blas-build-ms must be in [0, 1e6] milliseconds") << bad;
  }
  // The BLAS budgets manage what culling leaves out: without culling they are refused.
  o = CullingOptions{};
  o.blasBudgetBytes = 1 << 20;
  EXPECT_NE(message(o).find("need"), std::string::npos);
  o = CullingOptions{};
  o.blasBuildMilliseconds = 2.0;
  EXPECT_NE(message(o).find("--blas-build-ms"), std::string::npos);
  EXPECT_NE(message(o).find("need"), std::string::npos);
  EXPECT_THROW(parseCullingMode("all"), std::invalid_argument);
  EXPECT_EQ(parseCullingMode("lipac"), CullingMode::Lipac);
  o = lipac();
  o.hitboxSize = 0.001f;
  EXPECT_THROW(SceneCulling(row(), o), std::invalid_argument) << "too many hitboxes";
}

}  // namespace
}  // namespace memograph::runtime
