// The city built-in scene: the counts the culling benchmarks need at full size, scaled
// together by `scale`, a valid scene at every size, the same scene on every run, the mirror
// at the end of the main street, and a street-level camera path that looks at the mirror
// from the street and keeps clear of everything in the city at every scale.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "runtime/scene/builtin/scene_validation.h"
#include "runtime/shaders/accel/vertex_motion.h"

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
      const glm::vec3 view = glm::normalize(c.target - c.position);
      const bool inStreet = std::abs(c.position.x) < 0.5f * kCityStreetWidth &&
                            c.position.z < mirrorZ && c.position.z > 0.0f;
      const bool facingMirror = view.z > 0.9f;
      // Below the mirror's top (14 m), so that it fills the view ahead.
      mirrorFrames += inStreet && facingMirror &&
                      c.position.y < cityTerrainHeight(c.position.x, c.position.z) + 14.0f;
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

// The box around an instance in world space.
Bounds worldBounds(const Scene& scene, const Instance& instance) {
  const Bounds object = meshBounds(scene.meshes[instance.mesh]);
  Bounds out{glm::vec3(1e30f), glm::vec3(-1e30f)};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? object.hi.x : object.lo.x,
                      corner & 2 ? object.hi.y : object.lo.y,
                      corner & 4 ? object.hi.z : object.lo.z};
    const glm::vec3 world = glm::vec3(instance.objectToWorld * glm::vec4(p, 1.0f));
    out.lo = glm::min(out.lo, world);
    out.hi = glm::max(out.hi, world);
  }
  return out;
}

// The street path stays at street level (no more than 14 m above the ground, above the
// props' 8 m), at least 0.5 m from the box of every building, prop, flag and the mirror,
// and moves smoothly: sampled finely enough that consecutive frames are at most 1 m apart,
// at an even speed, the view turning at most 3 degrees a frame. Every scale places other
// buildings and props, so each is checked. (Measured: at least 1.2 m of clearance, the
// closest a flag pole at the mirror's corner at scale 1; at most 2.2 degrees a frame.)
TEST(CityScene, TheStreetPathKeepsClearOfTheCityAtEveryScale) {
  for (double scale : {0.02, 0.05, 0.2, 1.0}) {
    SCOPED_TRACE(scale);
    const Scene scene = makeBuiltinScene("city", cityOptions(scale));
    std::vector<Bounds> obstacles;
    std::vector<std::string> names;
    for (const Instance& i : scene.instances) {
      if (scene.meshes[i.mesh].name == "city_ground")
        continue;  // under everything: the heights above it are checked instead
      obstacles.push_back(worldBounds(scene, i));
      names.push_back(scene.meshes[i.mesh].name);
    }
    const int frames = 4000;
    const CameraPath path = makeBuiltinCameraPath("city", frames, scale);
    ASSERT_EQ(path.frames.size(), std::size_t(frames));
    float shortestStep = 1e30f, longestStep = 0.0f;
    for (int f = 0; f < frames; ++f) {
      const Camera& c = path.frames[std::size_t(f)];
      const float above = c.position.y - cityTerrainHeight(c.position.x, c.position.z);
      ASSERT_LE(above, 14.0f) << "frame " << f;
      ASSERT_GE(above, 8.5f) << "frame " << f;
      for (std::size_t b = 0; b < obstacles.size(); ++b) {
        const glm::vec3 outside = glm::max(
            glm::max(obstacles[b].lo - c.position, c.position - obstacles[b].hi), glm::vec3(0.0f));
        ASSERT_GE(glm::length(outside), 0.5f)
            << "frame " << f << " at " << c.position.x << ", " << c.position.y << ", "
            << c.position.z << ": " << names[b];
      }
      // The path is closed: the last frame leads back to the first.
      const Camera& next = path.frames[std::size_t((f + 1) % frames)];
      const float step = glm::distance(c.position, next.position);
      shortestStep = std::min(shortestStep, step);
      longestStep = std::max(longestStep, step);
      const float turn = glm::degrees(
          std::acos(std::min(1.0f, glm::dot(glm::normalize(c.target - c.position),
                                            glm::normalize(next.target - next.position)))));
      ASSERT_LE(turn, 3.0f) << "frame " << f;
    }
    EXPECT_LE(longestStep, 1.0f);
    EXPECT_GE(shortestStep, 0.95f * longestStep) << "constant speed";
  }
}

// `path=aerial` keeps the old path, in from 150 m above the city, for the figures measured
// on it; the street path is the default, for the scene's camera and for `bench`.
TEST(CityScene, TheAerialPathStaysSelectable) {
  const CameraPath street = makeBuiltinCameraPath("city", 360, 0.02);
  const CameraPath aerial = makeBuiltinCameraPath("city", 360, 0.02, CityCameraPath::Aerial);
  EXPECT_GT(aerial.frames.front().position.y, 100.0f);
  EXPECT_LT(street.frames.front().position.y, 14.0f);
  BuiltinSceneOptions options = cityOptions(0.02);
  EXPECT_EQ(makeBuiltinScene("city", options).camera.position, street.frames.front().position);
  options.cityPath = CityCameraPath::Aerial;
  EXPECT_EQ(makeBuiltinScene("city", options).camera.position, aerial.frames.front().position);
}

TEST(CityScene, FlagsMoveAndStayAtThePole) {
  const glm::vec3 atPole{0.0f, 0.7f, 0.0f}, atTip{2.4f, 0.7f, 0.0f};
  const auto offset = [](glm::vec3 rest, float seconds, int flag) {
    return gpu::vertexMotionOffset(cityFlagMotion(flag), rest, seconds);
  };
  EXPECT_EQ(offset(atPole, 1.3f, 0), glm::vec3(0.0f));
  const glm::vec3 a = offset(atTip, 0.0f, 0);
  const glm::vec3 b = offset(atTip, 0.5f, 0);
  EXPECT_GT(glm::distance(a, b), 0.05f);
  EXPECT_LT(glm::length(a), 1.0f);
  EXPECT_NE(offset(atTip, 0.5f, 0), offset(atTip, 0.5f, 1));
  // One motion per flag, in the flags' order.
  const Scene scene = makeBuiltinScene("city", cityOptions(0.02));
  ASSERT_EQ(scene.animatedMotions.size(), scene.animatedMeshes.size());
  EXPECT_EQ(scene.animatedMotions[1].wave, cityFlagMotion(1).wave);
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

TEST(CityScene, ThePathIsASpecKeyBesideTheScale) {
  std::string error;
  const auto street = parseBuiltinSceneSpec("city", error);
  ASSERT_TRUE(street.has_value()) << error;
  EXPECT_EQ(street->options.cityPath, CityCameraPath::Street);
  const auto aerial = parseBuiltinSceneSpec("city:scale=0.05,path=aerial", error);
  ASSERT_TRUE(aerial.has_value()) << error;
  EXPECT_EQ(aerial->options.cityPath, CityCameraPath::Aerial);
  EXPECT_DOUBLE_EQ(aerial->options.cityScale, 0.05);
  const auto explicitStreet = parseBuiltinSceneSpec("city:path=street,scale=0.02", error);
  ASSERT_TRUE(explicitStreet.has_value()) << error;
  EXPECT_EQ(explicitStreet->options.cityPath, CityCameraPath::Street);
  for (const char* bad : {"city:path=bogus", "city:path=", "city:path", "city:path=Street"}) {
    EXPECT_FALSE(parseBuiltinSceneSpec(bad, error).has_value()) << bad;
    EXPECT_NE(error.find("path is street"), std::string::npos) << bad << ": " << error;
  }
}

}  // namespace
}  // namespace memograph::runtime
