// The mesh LODs' choice on the host (runtime/accel/lod_choice.h; seeds/001 §3.1.1, §3.3.1) with
// made-up feedback: an instance takes the coarsest level whose world error fits its footprint; with
// no feedback, a pixel at its distance; a narrow cone from a magnifying mirror keeps a far
// instance at its finest where distance alone would simplify it; a wide one (a diffuse
// bounce's) never takes an instance coarser than its distance; the narrowest cone of recent
// counting frames decides; a part removed whole counts its length; switching coarser needs a
// margin; a light's quad and meshes without LODs stay whole; bad input is refused.
#include <cstring>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "runtime/accel/lod_choice.h"
#include "runtime/accel/scene_culling.h"

namespace memograph::runtime {
namespace {

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

Mesh unitBox() {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals.assign(3, {0, 0, 1});
  mesh.indices = {0, 1, 2};
  return mesh;
}

// Mesh 0 has LODs of object-space error 0.1, 0.3 and 0.9; mesh 1 none. Instances: 0 of mesh 0
// at z = -100, 1 of mesh 0 at z = -5, 2 of mesh 1 at z = -100, 3 a light's quad of mesh 0 at
// z = -100, 4 of mesh 0 scaled 3x at z = -100.
Scene lodScene() {
  Scene scene;
  scene.meshes = {unitBox(), unitBox()};
  scene.meshLods.resize(2);
  for (const float error : {0.1f, 0.3f, 0.9f})
    scene.meshLods[0].push_back({unitBox(), error});
  const auto at = [](float z, float scale = 1.0f) {
    return glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, z}), glm::vec3(scale));
  };
  scene.instances = {{0, 0, at(-100.0f)},
                     {0, 0, at(-5.0f)},
                     {1, 0, at(-100.0f)},
                     {0, 0, at(-100.0f), false},
                     {0, 0, at(-100.0f, 3.0f)}};
  return scene;
}

Camera origin() {
  Camera c;
  c.position = glm::vec3(0.0f);
  c.target = {0.0f, 0.0f, -1.0f};
  return c;
}

TEST(LodChoice, TheCoarsestLevelWithinTheFootprint) {
  const std::vector<float> errors = {0.1f, 0.3f, 1.0f};
  EXPECT_EQ(lodForFootprint(errors, 0.05f, 1.0f), 0u);
  EXPECT_EQ(lodForFootprint(errors, 0.1f, 1.0f), 1u);
  EXPECT_EQ(lodForFootprint(errors, 0.5f, 1.0f), 2u);
  EXPECT_EQ(lodForFootprint(errors, 50.0f, 1.0f), 3u);
  EXPECT_EQ(lodForFootprint(errors, 0.5f, 0.5f), 1u) << "half a footprint's error";
  EXPECT_EQ(lodForFootprint({}, 50.0f, 1.0f), 0u);
  EXPECT_EQ(lodForFootprint(errors, std::nanf(""), 1.0f), 0u);
  EXPECT_EQ(lodForFootprint(errors, -1.0f, 1.0f), 0u);
  EXPECT_EQ(lodForFootprint(errors, std::numeric_limits<float>::infinity(), 1.0f), 0u);
}

TEST(LodChoice, APixelAtTheDistanceWithoutFeedback) {
  const Scene scene = lodScene();
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  // 0.01 rad a pixel: 1 unit at 100, 0.05 at 5.
  choice.update(origin(), 0.01f, {});
  EXPECT_EQ(choice.wanted()[0], 3u) << "100 units away: a footprint of 1 takes the coarsest";
  EXPECT_EQ(choice.wanted()[1], 0u) << "4 units away";
  EXPECT_EQ(choice.wanted()[2], 0u) << "no LODs";
  EXPECT_EQ(choice.wanted()[3], 0u) << "a light's quad";
  EXPECT_EQ(choice.wanted()[4], 2u) << "3x its object error in the world: 0.3, 0.9, 2.7";
  EXPECT_FALSE(choice.fromFeedback(0));
  EXPECT_EQ(choice.levelCount(0), 4u);
  EXPECT_EQ(choice.levelCount(2), 1u);
}

// seeds/001 §3.1.1: distance alone fails under magnification. A curved mirror narrows the cones
// it sends to a far instance far below a pixel at the instance's distance; the feedback's
// footprint keeps the instance at its finest, where its distance would take the coarsest.
TEST(LodChoice, WhatAMirrorMagnifiesStaysDetailed) {
  const Scene scene = lodScene();
  InstanceLodChoice byDistance(scene, instanceBounds(scene), 1.0f);
  byDistance.update(origin(), 0.01f, {});
  ASSERT_EQ(byDistance.wanted()[0], 3u);

  InstanceLodChoice byCones(scene, instanceBounds(scene), 1.0f);
  std::vector<std::uint32_t> footprints(scene.instances.size(), kNoFootprint);
  footprints[0] = bits(0.02f);  // the magnified cone: a fiftieth of the distance's pixel
  byCones.update(origin(), 0.01f, footprints);
  EXPECT_EQ(byCones.wanted()[0], 0u);
  EXPECT_TRUE(byCones.fromFeedback(0));
  EXPECT_EQ(byCones.wanted()[1], 0u) << "no feedback: its distance";
  EXPECT_FALSE(byCones.fromFeedback(1));

  // But not the other way: a diffuse bounce's wide cone reaches the near instance, which the
  // camera sees beside it (or whose shadow it sees) at its distance's pixel (0.04).
  footprints[1] = bits(0.5f);
  byCones.update(origin(), 0.01f, footprints);
  EXPECT_EQ(byCones.wanted()[1], 0u) << "a wide cone is no coarser than its distance";
  EXPECT_FALSE(byCones.fromFeedback(1));
}

// Sampled feedback counts 1 of a pixel's P paths a counting frame, so a mirror's narrow cone
// reaches an instance only in some: the narrowest of the recent ones holds.
TEST(LodChoice, TheNarrowestRecentConeDecides) {
  const Scene scene = lodScene();
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  std::vector<std::uint32_t> footprints(scene.instances.size(), kNoFootprint);
  footprints[0] = bits(0.02f);
  choice.update(origin(), 0.01f, footprints);
  ASSERT_EQ(choice.wanted()[0], 0u);
  footprints[0] = bits(0.5f);  // a diffuse bounce's, narrower than the distance's pixel (1)
  for (int k = 0; k < InstanceLodChoice::kFeedbackMemory; ++k) {
    choice.update(origin(), 0.01f, footprints);
    EXPECT_EQ(choice.wanted()[0], 0u) << "update " << k + 1 << " with a wider cone";
  }
  choice.update(origin(), 0.01f, footprints);
  // Then the wide cone: 0.5 / 1.25 fits the 0.3 level.
  EXPECT_EQ(choice.wanted()[0], 2u) << "the narrow cone forgotten";
  EXPECT_TRUE(choice.fromFeedback(0));
}

// The margin, with the footprint a pixel at the instance's distance (0.01 rad a pixel): the
// camera moves along z towards instance 0 at z = -100.
TEST(LodChoice, ACoarserLevelNeedsTheMarginAFinerOneNone) {
  const Scene scene = lodScene();
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  const auto wantedAt = [&](float footprint) {
    Camera camera = origin();
    camera.position.z = -100.0f + footprint / 0.01f;
    camera.target = camera.position + glm::vec3(0.0f, 0.0f, -1.0f);
    choice.update(camera, 0.01f, {});
    return choice.wanted()[0];
  };
  ASSERT_EQ(wantedAt(0.05f), 0u);
  // 0.3 fits level 2 (0.3), but with the margin (0.3 / 1.25 = 0.24) only level 1.
  EXPECT_EQ(wantedAt(0.3f), 1u);
  // A footprint that wavers about the second level's edge keeps the first.
  EXPECT_EQ(wantedAt(0.301f), 1u);
  EXPECT_EQ(wantedAt(0.299f), 1u);
  EXPECT_EQ(wantedAt(0.38f), 2u) << "0.38 / 1.25 >= 0.3";
  // Finer at once.
  EXPECT_EQ(wantedAt(0.299f), 1u);
  EXPECT_EQ(wantedAt(0.01f), 0u);
}

// Sampled feedback reaches an instance seen in a few pixel blocks only now and then: between,
// it keeps the level the feedback chose (a mirror's), for kFeedbackMemory updates, then its
// distance decides.
TEST(LodChoice, WhatTheFeedbackMissesForAFewFramesKeepsItsLevel) {
  const Scene scene = lodScene();
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  std::vector<std::uint32_t> footprints(scene.instances.size(), kNoFootprint);
  footprints[0] = bits(0.02f);
  choice.update(origin(), 0.01f, footprints);
  ASSERT_EQ(choice.wanted()[0], 0u);
  const std::vector<std::uint32_t> none(scene.instances.size(), kNoFootprint);
  for (int k = 0; k < InstanceLodChoice::kFeedbackMemory; ++k) {
    choice.update(origin(), 0.01f, none);
    EXPECT_EQ(choice.wanted()[0], 0u) << "update " << k + 1 << " without feedback";
  }
  choice.update(origin(), 0.01f, none);
  // Then its distance: a footprint of 1 fits the 0.9 level, but not by the coarser margin.
  EXPECT_EQ(choice.wanted()[0], 2u) << "then its distance";
}

// A level that removes a part whole counts the part's length, what a viewer sees go, where it
// exceeds the simplifier's error (a window frame 1.5 m long that stood 0.2 m out).
TEST(LodChoice, APartRemovedWholeCountsItsLength) {
  Scene scene = lodScene();
  scene.meshLods[0][1].removedPart = 0.9f;  // level 2: error 0.3, but a part 0.9 long gone
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  std::vector<std::uint32_t> footprints(scene.instances.size(), kNoFootprint);
  footprints[0] = bits(0.5f);
  choice.update(origin(), 0.01f, footprints);
  EXPECT_EQ(choice.wanted()[0], 1u) << "0.5 fits the 0.3 error, not the 0.9 part";
}

TEST(LodChoice, BadInputIsRefused) {
  const Scene scene = lodScene();
  EXPECT_THROW(InstanceLodChoice(scene, instanceBounds(scene), 0.0f), std::invalid_argument);
  EXPECT_THROW(InstanceLodChoice(scene, instanceBounds(scene), std::nanf("")),
               std::invalid_argument);
  EXPECT_THROW(InstanceLodChoice(scene, {}, 1.0f), std::logic_error);
  InstanceLodChoice choice(scene, instanceBounds(scene), 1.0f);
  const std::vector<std::uint32_t> tooFew(2, kNoFootprint);
  EXPECT_THROW(choice.update(origin(), 0.01f, tooFew), std::logic_error);
  // A NaN footprint (bits the shader never writes) takes the finest level, not a crash.
  std::vector<std::uint32_t> nan(scene.instances.size(), kNoFootprint);
  nan[0] = 0x7FC00000u;
  choice.update(origin(), 0.01f, nan);
  EXPECT_EQ(choice.wanted()[0], 0u);
  CullingOptions o;
  o.lodPixelError = -1.0f;
  EXPECT_THROW(validateCullingOptions(o), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime
