// Whether a camera can be rendered, checked before a scene is built or uploaded so that a
// camera far outside any scene gets a message naming its coordinates, not a degenerate basis
// found at the first frame. Header-only: the built-in scenes' library (camera paths, scene
// validation) and the runtime's validate stage both use it.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

// The largest camera coordinate (metres): the view vector (target - position) of two points
// within it stays below 2e18 per axis, its squared length below 1.2e37, finite in float
// (3.4e38), so the camera's basis can be normalized. Scenes are float meshes, meaningful far
// below this (float resolution at 1e18 m is 1e11 m).
inline constexpr float kMaxCameraCoordinate = 1e18f;

// Empty for a camera the renderer can use; otherwise why not, naming the value: a
// coordinate not finite or beyond ±kMaxCameraCoordinate, a target at the position, an up
// vector along the view direction, a field of view outside (0, 180) degrees.
inline std::string cameraProblem(const Camera& camera) {
  const auto number = [](float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(v));
    return std::string(text);
  };
  const auto point = [&](glm::vec3 p) {
    return std::string("(")
        .append(number(p.x))
        .append(", ")
        .append(number(p.y))
        .append(", ")
        .append(number(p.z))
        .append(")");
  };
  for (const auto& [what, p] : {std::pair<const char*, glm::vec3>{"position", camera.position},
                                {"target", camera.target}}) {
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k]) || std::abs(p[k]) > kMaxCameraCoordinate)
        return std::string("the camera's ") + what + " " + point(p) +
               " is out of range: each coordinate must be finite and within ±" +
               number(kMaxCameraCoordinate) + " m";
    }
  }
  // In double: the difference of two in-range floats is exact enough and cannot overflow.
  const glm::dvec3 view = glm::dvec3(camera.target) - glm::dvec3(camera.position);
  const double length = glm::length(view);
  if (!(length > 0.0))
    return "the camera has no view direction: the target equals the camera position " +
           point(camera.position);
  const glm::dvec3 up = glm::dvec3(camera.up);
  const double upLength = glm::length(up);
  if (!(upLength > 0.0) || !std::isfinite(upLength) ||
      glm::length(glm::cross(view / length, up / upLength)) < 1e-5)
    return "the camera's view direction (from " + point(camera.position) + " to " +
           point(camera.target) + ") is parallel to the up vector " + point(camera.up);
  if (!(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f))
    return "the camera's vertical field of view " + number(camera.verticalFovDegrees) +
           " must be between 0 and 180 degrees";
  return {};
}

}  // namespace memograph::runtime
