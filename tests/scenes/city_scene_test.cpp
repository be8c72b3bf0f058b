// The city built-in scene: the counts the culling benchmarks need at full size, scaled
// together by `scale`, a valid scene at every size, the same scene on every run, the mirror
// at the end of the main street, and a camera path that stays above the ground and looks
// at the mirror from the street.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "runtime/scenes/builtin_scenes.h"
#include "runtime/scenes/camera_path.h"
#include "runtime/scenes/scene_validation.h"

namespace memograph::runtime {
namespace {

BuiltinSceneOptions cityOptions(double scale) {
  BuiltinSceneOptions options;
  options.cityScale = scale;
  return options;
}

std::size_t triangleCount(const Scene& scene, std::uint32_t mesh) {
  return scene.meshes[mesh].indices.size() / 3;
}

// Full size: at least 20,000 instances over at least 1 km², 2,000 meshes of unique
// geometry and a few hundred animated ones (issue text of the culling work; seeds/001 §3.3
// measures on scenes of this order).
TEST(CityScene, FullSizeHasTheCountsCullingNeeds) {
  const Scene scene = makeBuiltinScene("city", cityOptions(1.0));
  EXPECT_GE(scene.instances.size(), 20000u);
  EXPECT_GE(scene.meshes.size(), 2000u);
  EXPECT_GE(scene.animatedMeshes.size(), 200u);
  const float side = 2.0f * cityHalfSize(1.0);
  EXPECT_GE(side * side, 1.0e6f);
  // Instanced props: some mesh is used by thousands of instances.
  std::vector<std::size_t> uses(scene.meshes.size(), 0);
  for (const Instance& i : scene.instances)
    ++uses[i.mesh];
  EXPECT_GE(*std::max_element(uses.begin(), uses.end()), 1000u);
  // Every animated mesh is its own (one instance), so its BLAS can be updated alone.
  for (std::uint32_t m : scene.animatedMeshes)
    EXPECT_EQ(uses[m], 1u) << scene.meshes[m].name;
  std::size_t triangles = 0;
  for (std::uint32_t m = 0; m < scene.meshes.size(); ++m)
    triangles += triangleCount(scene, m);
  // Enough unique geometry that the acceleration structures' memory matters (the
  // renderer reports its BLAS bytes: lavapipe's compacted BLASes of scale=0.02 took about
  // 104 B a triangle, 41,952,256 B for 403,396 triangles).
  EXPECT_GE(triangles, 10'000'000u) << triangles;
}

TEST(CityScene, ScaleShrinksTheCountsTogether) {
  const CityCounts full = cityCounts(1.0);
  const CityCounts small = cityCounts(0.02);
  EXPECT_EQ(small.buildings, 40);
  EXPECT_EQ(small.flags, 6);
  EXPECT_NEAR(double(small.props) / double(full.props), 0.02, 0.001);
  const Scene scene = makeBuiltinScene("city", cityOptions(0.02));
  EXPECT_EQ(scene.animatedMeshes.size(), 6u);
  EXPECT_GE(scene.instances.size(), 400u);
  EXPECT_LE(scene.instances.size(), 600u);
  std::set<std::string> buildingNames;
  for (const Mesh& m : scene.meshes)
    if (m.name.rfind("building_", 0) == 0)
      buildingNames.insert(m.name);
  EXPECT_EQ(buildingNames.size(), 40u);
  EXPECT_THROW(cityCounts(0.0), std::invalid_argument);
  EXPECT_THROW(cityCounts(1.5), std::invalid_argument);
}

TEST(CityScene, IsValidAndTheSameOnEveryRun) {
  for (double scale : {0.02, 0.1}) {
    SCOPED_TRACE(scale);
    const Scene a = makeBuiltinScene("city", cityOptions(scale));
    compiler::Diagnostics diagnostics;
    EXPECT_TRUE(validateScene(a, "city", diagnostics)) << compiler::formatDiagnostics(diagnostics);
    const Scene b = makeBuiltinScene("city", cityOptions(scale));
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (std::size_t m = 0; m < a.meshes.size(); ++m)
      ASSERT_EQ(a.meshes[m].positions, b.meshes[m].positions) << a.meshes[m].name;
    for (std::size_t i = 0; i < a.instances.size(); ++i)
      ASSERT_EQ(a.instances[i].objectToWorld, b.instances[i].objectToWorld) << i;
  }
}

// The mirror stands across the end of the main street, and the path looks at it from the
// street for a stretch of frames: those are the frames where culling by the frustum loses
// what the mirror shows (the city behind the camera).
TEST(CityScene, ThePathLooksAtTheMirrorFromTheStreet) {
  for (double scale : {0.02, 1.0}) {
    SCOPED_TRACE(scale);
    const float h = cityHalfSize(scale);
    const float mirrorZ = h - 0.5f * kCityStreetWidth;
    const CameraPath path = makeBuiltinCameraPath("city", 300, scale);
    ASSERT_EQ(path.frames.size(), 300u);
    int mirrorFrames = 0;
    for (const Camera& c : path.frames) {
      ASSERT_GE(c.position.y, cityTerrainHeight(c.position.x, c.position.z) + 1.69f);
      const glm::vec3 view = glm::normalize(c.target - c.position);
      const bool inStreet = std::abs(c.position.x) < 0.5f * kCityStreetWidth &&
                            c.position.z < mirrorZ && c.position.z > 0.0f;
      const bool facingMirror = view.z > 0.9f;
      mirrorFrames += inStreet && facingMirror &&
                      c.position.y < cityTerrainHeight(c.position.x, c.position.z) + 6.0f;
    }
    EXPECT_GE(mirrorFrames, 10) << "frames in the main street looking at the mirror";
  }
  const Scene scene = makeBuiltinScene("city", cityOptions(0.02));
  bool mirror = false;
  for (const Instance& i : scene.instances)
    mirror |= scene.meshes[i.mesh].name == "mirror_wall" &&
              scene.materials[i.material].name == "City_Mirror";
  EXPECT_TRUE(mirror);
}

TEST(CityScene, FlagsMoveAndStayAtThePole) {
  const glm::vec3 atPole{0.0f, 0.7f, 0.0f}, atTip{2.4f, 0.7f, 0.0f};
  EXPECT_EQ(cityFlagDisplacement(atPole, 1.3f, 0), glm::vec3(0.0f));
  const glm::vec3 a = cityFlagDisplacement(atTip, 0.0f, 0);
  const glm::vec3 b = cityFlagDisplacement(atTip, 0.5f, 0);
  EXPECT_GT(glm::distance(a, b), 0.05f);
  EXPECT_LT(glm::length(a), 1.0f);
  EXPECT_NE(cityFlagDisplacement(atTip, 0.5f, 0), cityFlagDisplacement(atTip, 0.5f, 1));
}

TEST(CityScene, ScaleIsASpecKey) {
  std::string error;
  const auto spec = parseBuiltinSceneSpec("city:scale=0.02", error);
  ASSERT_TRUE(spec.has_value()) << error;
  EXPECT_DOUBLE_EQ(spec->options.cityScale, 0.02);
  for (const char* bad : {"city:scale=0", "city:scale=1.5", "city:scale=abc", "city:scale=-1"}) {
    EXPECT_FALSE(parseBuiltinSceneSpec(bad, error).has_value()) << bad;
    EXPECT_NE(error.find("scale is a number in (0, 1]"), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace memograph::runtime
