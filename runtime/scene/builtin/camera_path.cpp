#include "runtime/scene/builtin/camera_path.h"

#include "compiler/input_file.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/camera_range.h"

namespace memograph::runtime {
namespace {

struct Field {
  std::string_view text;
  std::uint32_t column = 0;  // 1-based
};

// Splits a line (comment already removed) at spaces and tabs.
std::vector<Field> splitFields(std::string_view line) {
  std::vector<Field> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
      ++i;
    if (i > start)
      fields.push_back({line.substr(start, i - start), static_cast<std::uint32_t>(start + 1)});
  }
  return fields;
}

// A number of a frame: nothing and `error` set when it is not one, or is one a float cannot
// hold. A value too small for a float (1e-310, a double's denormal) is a number and becomes
// the nearest float (0 or a float denormal), as a decimal too precise is rounded.
std::optional<float> parseFloat(std::string_view s, std::string& error) {
  const char* end = s.data() + s.size();
  // from_chars rejects a leading '+'; accept it since people write it.
  const char* begin = (!s.empty() && s[0] == '+') ? s.data() + 1 : s.data();
  double value = 0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ptr != end || (ec != std::errc() && ec != std::errc::result_out_of_range) || s.empty()) {
    error = "expected a number, found '" + std::string(s) + "'";
    return std::nullopt;
  }
  // Out of a double's range, from_chars leaves `value` alone; strtod says which way.
  if (ec == std::errc::result_out_of_range)
    value = std::strtod(std::string(begin, end).c_str(), nullptr);
  if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
    error = "the number " + std::string(s) +
            " is out of range: camera-path values are floats, finite and within ±3.4e38";
    return std::nullopt;
  }
  return static_cast<float>(value);
}

}  // namespace

std::optional<CameraPath> parseCameraPath(const compiler::SourceFile& file,
                                          compiler::Diagnostics& diagnostics) {
  CameraPath path;
  const std::size_t errorsBefore = diagnostics.errorCount();
  const std::string_view text = file.text;
  std::uint32_t lineNumber = 0;
  for (std::size_t start = 0; start < text.size();) {
    ++lineNumber;
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos)
      end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
      line = line.substr(0, hash);
    }
    const std::vector<Field> fields = splitFields(line);
    if (fields.empty())
      continue;
    if (fields.size() != 7) {
      const std::uint32_t column = fields.size() > 7 ? fields[7].column : fields.back().column;
      auto& d = diagnostics.error(
          file, {lineNumber, column},
          "a camera-path frame has 7 numbers (px py pz tx ty tz fov), this line has " +
              std::to_string(fields.size()));
      d.notes.push_back("comments start with '#'");
      continue;
    }
    float v[7];
    bool ok = true;
    for (int i = 0; i < 7; ++i) {
      std::string error;
      const auto value = parseFloat(fields[i].text, error);
      if (!value) {
        diagnostics.error(file, {lineNumber, fields[i].column}, error);
        ok = false;
        break;
      }
      v[i] = *value;
    }
    if (!ok)
      continue;
    Camera camera;
    camera.position = {v[0], v[1], v[2]};
    camera.target = {v[3], v[4], v[5]};
    camera.verticalFovDegrees = v[6];
    if (!(v[6] > 0.0f && v[6] < 180.0f)) {
      diagnostics.error(file, {lineNumber, fields[6].column},
                        "the vertical field of view must be between 0 and 180 degrees, got " +
                            std::string(fields[6].text));
      continue;
    }
    // Range, view direction and up vector, before any scene is built.
    if (const std::string problem = cameraProblem(camera); !problem.empty()) {
      const bool position = problem.find("position (") != std::string::npos &&
                            problem.find("out of range") != std::string::npos;
      auto& d = diagnostics.error(file, {lineNumber, fields[position ? 0 : 3].column}, problem);
      if (problem.find("parallel") != std::string::npos)
        d.notes.push_back("move the target a little sideways");
      continue;
    }
    path.frames.push_back(camera);
  }
  if (diagnostics.errorCount() > errorsBefore)
    return std::nullopt;
  if (path.frames.empty()) {
    diagnostics.error(file, {1, 1}, "the camera path has no frames")
        .notes.push_back("each frame is a line: px py pz tx ty tz fov");
    return std::nullopt;
  }
  return path;
}

std::optional<CameraPath> loadCameraPath(const std::string& path,
                                         compiler::Diagnostics& diagnostics) {
  // A regular file within the text limit only: a FIFO or /dev/zero must not hang or
  // exhaust memory (docs/guide/limits.md).
  std::string error;
  auto text = files::readInputFile(path, files::kMaxTextFileBytes, "camera paths", error);
  if (!text) {
    diagnostics.error(path, "cannot read the camera-path file: " + error);
    return std::nullopt;
  }
  return parseCameraPath(compiler::SourceFile{path, std::move(*text)}, diagnostics);
}

std::string formatCameraPath(const CameraPath& path, std::string_view headerComment) {
  std::string out;
  if (!headerComment.empty()) {
    std::istringstream lines{std::string(headerComment)};
    for (std::string line; std::getline(lines, line);)
      out += "# " + line + '\n';
  }
  out += "# px py pz  tx ty tz  vertical-fov-degrees\n";
  char buffer[256];
  for (const Camera& c : path.frames) {
    // %.9g round-trips every float.
    std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g  %.9g %.9g %.9g  %.9g\n", c.position.x,
                  c.position.y, c.position.z, c.target.x, c.target.y, c.target.z,
                  c.verticalFovDegrees);
    out += buffer;
  }
  return out;
}

namespace {

// A closed Catmull-Rom curve through `points`, evaluated at parameter s ∈ [0, n).
glm::vec3 catmullRom(const std::vector<glm::vec3>& points, float s) {
  const int n = static_cast<int>(points.size());
  const int i = static_cast<int>(std::floor(s));
  const float t = s - static_cast<float>(i);
  const auto p = [&](int k) { return points[((k % n) + n) % n]; };
  const glm::vec3 p0 = p(i - 1), p1 = p(i), p2 = p(i + 1), p3 = p(i + 2);
  return 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t * t +
                 (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t * t * t);
}

// Samples `frames` cameras at equal arc length along closed curves through the eye and
// target key points, so the camera moves at constant speed like a walking person.
CameraPath sampleClosedPath(const std::vector<glm::vec3>& eyes,
                            const std::vector<glm::vec3>& targets, float fov, int frames) {
  const int n = static_cast<int>(eyes.size());
  constexpr int kSteps = 64;  // per segment, to tabulate arc length
  std::vector<float> length{0.0f};
  glm::vec3 previous = catmullRom(eyes, 0.0f);
  for (int k = 1; k <= n * kSteps; ++k) {
    const glm::vec3 point = catmullRom(eyes, static_cast<float>(k) / kSteps);
    length.push_back(length.back() + glm::length(point - previous));
    previous = point;
  }
  CameraPath path;
  std::size_t k = 1;  // frames go forwards, so the search goes on from the last frame's
  for (int f = 0; f < frames; ++f) {
    const float wanted = length.back() * static_cast<float>(f) / static_cast<float>(frames);
    while (k + 1 < length.size() && length[k] < wanted)
      ++k;
    const float segment = length[k] - length[k - 1];
    const float t = segment > 0 ? (wanted - length[k - 1]) / segment : 0.0f;
    const float s = (static_cast<float>(k - 1) + t) / kSteps;
    Camera camera;
    camera.position = catmullRom(eyes, s);
    camera.target = catmullRom(targets, s);
    // Interpolated targets can pass close to the eye; keep them at least 1 m away so the
    // view direction stays well defined.
    const glm::vec3 view = camera.target - camera.position;
    if (glm::length(view) < 1.0f)
      camera.target = camera.position + glm::normalize(view);
    camera.verticalFovDegrees = fov;
    path.frames.push_back(camera);
  }
  return path;
}

// From high outside the city down into the main street (x = 0), along it towards the
// mirror wall at its end (the frames where the mirror shows what is behind the camera), past
// the wall's side into the cross street, and up and out again.
CameraPath cityAerialPath(int frames, double cityScale) {
  const float h = cityHalfSize(cityScale);
  const std::vector<glm::vec3> eyes = {
      {-1.6f * h, 150.0f, -1.6f * h}, {-0.6f * h, 80.0f, -1.3f * h}, {0.0f, 25.0f, -1.1f * h},
      {0.0f, 2.0f, -0.85f * h},       {0.0f, 2.0f, -0.3f * h},       {0.0f, 2.0f, 0.3f * h},
      {0.0f, 2.0f, h - 45.0f},        {8.0f, 2.0f, h - 15.0f},       {30.0f, 4.0f, h},
      {0.8f * h, 60.0f, 1.3f * h},    {-0.5f * h, 150.0f, 1.6f * h}, {-1.7f * h, 170.0f, 0.0f}};
  const std::vector<glm::vec3> targets = {
      {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.5f * h}, {0.0f, 5.0f, -0.6f * h}, {0.0f, 2.0f, 0.0f},
      {0.0f, 2.0f, h},    {0.0f, 2.0f, h},         {0.0f, 3.0f, h},         {8.0f, 2.0f, h + 30.0f},
      {h, 10.0f, h},      {0.0f, 0.0f, 0.0f},      {0.0f, 0.0f, 0.0f},      {0.0f, 0.0f, 0.0f}};
  // Heights near the ground are above it; the spline keeps at least 1.7 m of clearance.
  std::vector<glm::vec3> groundEyes = eyes, groundTargets = targets;
  for (glm::vec3& e : groundEyes)
    e.y += cityTerrainHeight(e.x, e.z);
  for (glm::vec3& t : groundTargets)
    t.y += cityTerrainHeight(t.x, t.z);
  CameraPath path = sampleClosedPath(groundEyes, groundTargets, 60.0f, frames);
  for (Camera& c : path.frames)
    c.position.y = std::max(c.position.y, cityTerrainHeight(c.position.x, c.position.z) + 1.7f);
  return path;
}

// Keys along a closed polyline of corners (x, height above the ground, z), on the ground,
// at most `spacing` metres apart: a uniform Catmull-Rom through keys this dense follows the
// polyline, straight where it is straight and rounded within a spacing of each corner, so
// the corners alone say where the camera goes and how far it stays from the buildings.
std::vector<glm::vec3> cityKeysAlong(const std::vector<glm::vec3>& corners, float spacing) {
  std::vector<glm::vec3> keys;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const glm::vec3 a = corners[i], b = corners[(i + 1) % corners.size()];
    const float length = glm::distance(glm::vec2(a.x, a.z), glm::vec2(b.x, b.z));
    const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    for (int k = 0; k < steps; ++k) {
      const glm::vec3 p = glm::mix(a, b, static_cast<float>(k) / static_cast<float>(steps));
      keys.push_back({p.x, cityTerrainHeight(p.x, p.z) + p.y, p.z});
    }
  }
  return keys;
}

// In from 60 m south of the city at 12 m, down the main street (x = 0) at 9 m towards the
// mirror wall at its end (the frames where the mirror shows what is behind the camera),
// past the wall's east side into the street along the city's north edge, east to the next
// street (x = kCityBlockSize), down it to the south edge and back round to the start. At
// 9 m the camera is above every prop (flag poles, the tallest, are 8 m) and below most
// buildings' roofs, which hide the rest of the city, as a player's street does.
CameraPath cityStreetPath(int frames, double cityScale) {
  const float h = cityHalfSize(cityScale);
  const float east = kCityBlockSize;
  // The mirror (|x| <= 6 m) and the corner buildings of the block east of the main street
  // (x >= 10.7 m, z <= h - 10.7 m) leave a gap 4.7 m wide round the wall's east end: the
  // camera passes it at x = 8.5 m.
  const float pastMirror = 8.5f;
  const std::vector<glm::vec3> corners = {
      {0.0f, 12.0f, -h - 60.0f},     {0.0f, 9.0f, -h + 30.0f},         {0.0f, 9.0f, h - 50.0f},
      {pastMirror, 9.0f, h - 22.0f}, {pastMirror, 9.0f, h - 6.0f},     {22.0f, 9.0f, h},
      {east - 16.0f, 9.0f, h},       {east, 9.0f, h - 16.0f},          {east, 9.0f, -h + 30.0f},
      {east, 11.0f, -h - 40.0f},     {0.6f * east, 12.0f, -h - 95.0f}, {0.0f, 12.0f, -h - 95.0f}};
  const std::vector<glm::vec3> eyes = cityKeysAlong(corners, 5.0f);
  // Looking ahead along the path, about 40 m (8 keys) on and 3 m down: down the main street
  // that is at the mirror, and the view turns into each street before the camera does.
  std::vector<glm::vec3> targets;
  for (std::size_t i = 0; i < eyes.size(); ++i)
    targets.push_back(eyes[(i + 8) % eyes.size()] - glm::vec3(0.0f, 3.0f, 0.0f));
  return sampleClosedPath(eyes, targets, 60.0f, frames);
}

}  // namespace

CameraPath makeBuiltinCameraPath(std::string_view scene, int frames, double cityScale,
                                 CityCameraPath cityPath) {
  if (frames < 1)
    throw std::invalid_argument("a camera path needs at least one frame");
  if (scene == "classroom") {
    // Eye height 1.6 m: in along the window aisle, across the front past the blackboard,
    // back down the middle aisle, a look at the bookcases, and out along the left wall.
    const float eye = 1.6f;
    const std::vector<glm::vec3> eyes = {{8.4f, eye, 6.8f}, {8.4f, eye, 4.5f}, {8.3f, eye, 2.2f},
                                         {6.5f, eye, 1.0f}, {4.5f, eye, 0.9f}, {3.2f, eye, 1.2f},
                                         {4.5f, eye, 2.4f}, {4.5f, eye, 4.5f}, {4.5f, eye, 6.6f},
                                         {2.5f, eye, 6.7f}, {0.6f, eye, 5.5f}, {0.6f, eye, 2.5f},
                                         {2.5f, eye, 2.2f}, {5.5f, eye, 6.8f}};
    const std::vector<glm::vec3> targets = {
        {4.0f, 1.2f, 1.0f}, {5.0f, 1.0f, 1.0f}, {4.5f, 1.4f, 0.0f}, {4.5f, 1.6f, 0.0f},
        {3.0f, 1.6f, 0.0f}, {8.9f, 1.6f, 3.5f}, {6.0f, 0.8f, 4.0f}, {4.5f, 1.2f, 7.5f},
        {2.2f, 1.2f, 7.5f}, {1.5f, 1.5f, 0.0f}, {4.5f, 1.5f, 0.0f}, {4.5f, 1.5f, 0.0f},
        {8.9f, 1.7f, 3.8f}, {9.0f, 1.4f, 5.0f}};
    return sampleClosedPath(eyes, targets, 60.0f, frames);
  }
  if (scene == "landscape") {
    // A loop around the valley at 25–40 m above the ground, passing over both groves,
    // looking ahead and slightly down.
    std::vector<glm::vec3> eyes, targets;
    const int keys = 12;
    for (int k = 0; k < keys; ++k) {
      const float a = 6.2831853f * static_cast<float>(k) / keys;
      const float radius = 110.0f + 30.0f * std::sin(3.0f * a);
      const float x = radius * std::cos(a), z = radius * std::sin(a);
      const float ground = landscapeTerrainHeight(x, z);
      eyes.push_back({x, ground + 28.0f + 8.0f * std::cos(2.0f * a), z});
      const float b = a + 0.5f;
      const float tx = 0.7f * radius * std::cos(b), tz = 0.7f * radius * std::sin(b);
      targets.push_back({tx, landscapeTerrainHeight(tx, tz), tz});
    }
    CameraPath path = sampleClosedPath(eyes, targets, 55.0f, frames);
    // The spline may dip between keys: keep at least 8 m of clearance over the ground.
    for (Camera& c : path.frames) {
      const float ground = landscapeTerrainHeight(c.position.x, c.position.z);
      c.position.y = std::max(c.position.y, ground + 8.0f);
    }
    return path;
  }
  if (scene == "city")
    return cityPath == CityCameraPath::Street ? cityStreetPath(frames, cityScale)
                                              : cityAerialPath(frames, cityScale);
  std::string known;
  for (const std::string& n : builtinSceneNames())
    known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("no built-in camera path for scene '" + std::string(scene) +
                              "'; known scenes: " + known);
}

}  // namespace memograph::runtime
