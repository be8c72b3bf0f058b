// Camera-path files: the format round-trips, and every mistake is reported at its place.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"

namespace memograph::runtime {
namespace {

using compiler::Diagnostics;
using compiler::SourceFile;

std::string firstError(const std::string& text) {
  Diagnostics diagnostics;
  const auto path = parseCameraPath(SourceFile{"walk.campath", text}, diagnostics);
  EXPECT_FALSE(path.has_value());
  EXPECT_TRUE(diagnostics.hasErrors());
  return diagnostics.all().empty() ? "" : compiler::formatDiagnostic(diagnostics.all()[0]);
}

TEST(CameraPath, ParsesFramesCommentsAndBlankLines) {
  const std::string text =
      "# a walk\n"
      "\n"
      "1 2 3   4 5 6   60   # first frame\n"
      "\t-1.5 +2 3e0 4 5 6.5 45.5\r\n";
  Diagnostics diagnostics;
  const auto path = parseCameraPath(SourceFile{"walk.campath", text}, diagnostics);
  ASSERT_TRUE(path.has_value()) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(path->frames.size(), 2u);
  EXPECT_EQ(path->frames[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(path->frames[0].target, glm::vec3(4, 5, 6));
  EXPECT_EQ(path->frames[0].verticalFovDegrees, 60.0f);
  EXPECT_EQ(path->frames[1].position, glm::vec3(-1.5f, 2, 3));
  EXPECT_EQ(path->frames[1].verticalFovDegrees, 45.5f);
}

TEST(CameraPath, WrongFieldCountNamesLineAndColumn) {
  const std::string e = firstError("# header\n1 2 3 4 5 6 60\n1 2 3 4 5 6\n");
  EXPECT_EQ(e.rfind("walk.campath:3:11: error: a camera-path frame has 7 numbers", 0), 0u) << e;
  const std::string extra = firstError("1 2 3 4 5 6 60 7\n");
  EXPECT_EQ(extra.rfind("walk.campath:1:16: error:", 0), 0u) << extra;
}

TEST(CameraPath, NonNumberIsReportedAtItsColumn) {
  const std::string e = firstError("1 2 3 4 five 6 60\n");
  EXPECT_EQ(e.rfind("walk.campath:1:9: error: expected a number, found 'five'", 0), 0u) << e;
  EXPECT_NE(e.find("        ^"), std::string::npos) << e;  // the caret under the field
  EXPECT_EQ(firstError("1 2 3 4 5 6 nan\n").rfind("walk.campath:1:13:", 0), 0u);
  EXPECT_EQ(firstError("1 2 3 4 5 6 60x\n").rfind("walk.campath:1:13:", 0), 0u);
}

TEST(CameraPath, FieldOfViewMustBeBetween0And180) {
  EXPECT_NE(firstError("0 0 0 1 0 0 0\n").find("between 0 and 180"), std::string::npos);
  EXPECT_NE(firstError("0 0 0 1 0 0 180\n").find("between 0 and 180"), std::string::npos);
  EXPECT_NE(firstError("0 0 0 1 0 0 -5\n").find(":1:13:"), std::string::npos);
}

TEST(CameraPath, DegenerateViewsAreRejected) {
  EXPECT_NE(firstError("1 1 1 1 1 1 60\n").find("target equals the camera position"),
            std::string::npos);
  EXPECT_NE(firstError("0 0 0 0 5 0 60\n").find("parallel to the up vector"), std::string::npos);
}

// A double's denormal is a number: it becomes the nearest float (here 0), not "expected a
// number"; a value past a float's range is reported as out of range, at its column.
TEST(CameraPath, TinyNumbersAreAcceptedAndHugeOnesAreOutOfRange) {
  compiler::Diagnostics diagnostics;
  const auto path =
      parseCameraPath(compiler::SourceFile{"walk.campath", "0 1e-310 5 0 0 0 45\n"}, diagnostics);
  ASSERT_TRUE(path) << compiler::formatDiagnostics(diagnostics);
  EXPECT_EQ(path->frames[0].position.y, 0.0f);
  EXPECT_EQ(firstError("0 0 5 1e39 0 0 45\n")
                .rfind("walk.campath:1:7: error: the number 1e39 "
                       "is out of range",
                       0),
            0u);
}

// A camera at 1e30 m made a degenerate basis at the first frame, reported as a parallel up
// vector; its position is out of range, said at its column.
TEST(CameraPath, CameraBeyondTheCoordinateRangeIsReportedAsOutOfRange) {
  const std::string e = firstError("1e30 0 0 0 0 0 45\n");
  EXPECT_EQ(e.rfind("walk.campath:1:1: error: the camera's position (1e+30, 0, 0) is out of "
                    "range: each coordinate must be finite and within ±1e+18 m",
                    0),
            0u)
      << e;
  EXPECT_NE(firstError("0 0 0 -2e18 1 0 45\n").find("the camera's target"), std::string::npos);
}

TEST(CameraPath, EmptyFileHasNoFrames) {
  EXPECT_NE(firstError("# only a comment\n\n").find("has no frames"), std::string::npos);
  EXPECT_NE(firstError("").find("has no frames"), std::string::npos);
}

TEST(CameraPath, EveryBadLineIsReported) {
  Diagnostics diagnostics;
  parseCameraPath(SourceFile{"p", "1 2\n0 0 0 1 0 0 60\nx 0 0 1 0 0 60\n"}, diagnostics);
  EXPECT_EQ(diagnostics.errorCount(), 2u);
}

TEST(CameraPath, MissingFileIsAnErrorNamingIt) {
  Diagnostics diagnostics;
  EXPECT_FALSE(loadCameraPath("/nonexistent/walk.campath", diagnostics).has_value());
  ASSERT_EQ(diagnostics.errorCount(), 1u);
  EXPECT_EQ(compiler::formatDiagnostic(diagnostics.all()[0]),
            "/nonexistent/walk.campath: error: cannot read the camera-path file: no such file\n");
}

TEST(CameraPath, FormatRoundTripsExactly) {
  const CameraPath path = makeBuiltinCameraPath("classroom", 50);
  const std::string text = formatCameraPath(path, "test path\nsecond line");
  EXPECT_EQ(text.rfind("# test path\n# second line\n", 0), 0u);
  const auto file = std::filesystem::temp_directory_path() / "memograph_roundtrip.campath";
  std::ofstream(file) << text;
  Diagnostics diagnostics;
  const auto back = loadCameraPath(file.string(), diagnostics);
  std::filesystem::remove(file);
  ASSERT_TRUE(back.has_value()) << compiler::formatDiagnostics(diagnostics);
  ASSERT_EQ(back->frames.size(), path.frames.size());
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    EXPECT_EQ(back->frames[i].position, path.frames[i].position);
    EXPECT_EQ(back->frames[i].target, path.frames[i].target);
    EXPECT_EQ(back->frames[i].verticalFovDegrees, path.frames[i].verticalFovDegrees);
  }
}

TEST(CameraPath, ClassroomWalkStaysInsideTheRoomAtWalkingSpeed) {
  const CameraPath path = makeBuiltinCameraPath("classroom", 360);
  ASSERT_EQ(path.frames.size(), 360u);
  float maxStep = 0, minStep = 1e9f;
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    const glm::vec3 p = path.frames[i].position;
    EXPECT_GT(p.x, 0.2f);
    EXPECT_LT(p.x, kClassroom.width - 0.2f);
    EXPECT_GT(p.z, 0.2f);
    EXPECT_LT(p.z, kClassroom.depth - 0.2f);
    EXPECT_GT(glm::length(path.frames[i].target - p), 0.5f);
    const glm::vec3 next = path.frames[(i + 1) % path.frames.size()].position;
    maxStep = std::max(maxStep, glm::length(next - p));
    minStep = std::min(minStep, glm::length(next - p));
  }
  // Constant speed: equal arc length per frame (chords differ a little on curves).
  EXPECT_LT(maxStep, 1.3f * minStep);
  // A walk: 1–10 cm per frame at 360 frames.
  EXPECT_GT(minStep, 0.01f);
  EXPECT_LT(maxStep, 0.15f);
}

TEST(CameraPath, LandscapeFlyOverStaysAboveTheGround) {
  const CameraPath path = makeBuiltinCameraPath("landscape", 400);
  ASSERT_EQ(path.frames.size(), 400u);
  for (const Camera& c : path.frames) {
    EXPECT_GE(c.position.y - landscapeTerrainHeight(c.position.x, c.position.z), 7.99f);
    EXPECT_LT(std::abs(c.position.x), kLandscapeHalfSize);
    EXPECT_LT(std::abs(c.position.z), kLandscapeHalfSize);
  }
}

TEST(CameraPath, UnknownSceneIsRejected) {
  EXPECT_THROW(makeBuiltinCameraPath("kitchen"), std::invalid_argument);
  EXPECT_THROW(makeBuiltinCameraPath("classroom", 0), std::invalid_argument);
}

}  // namespace
}  // namespace memograph::runtime

namespace memograph::runtime {
namespace {

void expectSameFrames(const CameraPath& file, const CameraPath& expected) {
  ASSERT_EQ(file.frames.size(), expected.frames.size());
  for (std::size_t i = 0; i < expected.frames.size(); ++i) {
    ASSERT_LT(glm::distance(file.frames[i].position, expected.frames[i].position), 1e-3f) << i;
    ASSERT_LT(glm::distance(file.frames[i].target, expected.frames[i].target), 1e-3f) << i;
  }
}

// The committed example files parse and match the generator (they are its output).
TEST(CameraPathExamples, MatchTheBuiltinGenerator) {
  for (const std::string& scene : builtinSceneNames()) {
    SCOPED_TRACE(scene);
    compiler::Diagnostics diagnostics;
    const auto path = loadCameraPath(
        std::string(MEMOGRAPH_EXAMPLES_DIR) + "/camera_paths/" + scene + ".campath", diagnostics);
    ASSERT_TRUE(path.has_value()) << compiler::formatDiagnostics(diagnostics);
    ASSERT_GE(path->frames.size(), 300u);  // the memoization benchmarks run ≥ 300 frames
    const CameraPath expected = makeBuiltinCameraPath(scene, static_cast<int>(path->frames.size()));
    expectSameFrames(*path, expected);
  }
  compiler::Diagnostics diagnostics;
  const auto aerial = loadCameraPath(
      std::string(MEMOGRAPH_EXAMPLES_DIR) + "/camera_paths/city_aerial.campath", diagnostics);
  ASSERT_TRUE(aerial.has_value()) << compiler::formatDiagnostics(diagnostics);
  expectSameFrames(*aerial, makeBuiltinCameraPath("city", static_cast<int>(aerial->frames.size()),
                                                  1.0, CityCameraPath::Aerial));
}

}  // namespace
}  // namespace memograph::runtime
