// Camera paths: one camera per frame, read from a plain-text file or generated for the
// built-in scenes. They play the part of the thesis's recorded first-person camera motion
// (§6), so that every benchmark run sees the same frames.
//
// File format (`.campath`, UTF-8/ASCII text):
//   - `#` starts a comment that runs to the end of the line; blank lines are ignored.
//   - Every other line is one frame, in order: seven numbers separated by spaces or tabs,
//       px py pz   tx ty tz   fov
//     the camera position, the point it looks at (world space, metres) and the vertical
//     field of view in degrees (0 < fov < 180). Up is +y; the view direction must not be
//     parallel to it.
//   - A file must hold at least one frame.
// Example:
//   # walk towards the blackboard
//   8.2 1.6 7.0   3.5 1.1 0.5   60
//   8.1 1.6 6.9   3.5 1.1 0.5   60
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/source_file.h"
#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

struct CameraPath {
  std::vector<Camera> frames;
};

// Parses camera-path text; errors carry file:line:col of the offending field. Returns
// nothing when `diagnostics` gained an error.
std::optional<CameraPath> parseCameraPath(const compiler::SourceFile& file,
                                          compiler::Diagnostics& diagnostics);

// Reads and parses a file; a missing or unreadable file is an error naming it.
std::optional<CameraPath> loadCameraPath(const std::string& path,
                                         compiler::Diagnostics& diagnostics);

// The text of a path in the format above, with a comment header; parses back to the same
// frames (numbers printed with enough digits to round-trip a float).
std::string formatCameraPath(const CameraPath& path, std::string_view headerComment = {});

// A path for a built-in scene ("classroom": a walk through the aisles past the blackboard
// and the bookcases; "landscape": a fly-over of the terrain and the two groves; "city": see
// CityCameraPath: by default in from the south at 12 m, down the main street at 9 m towards
// the mirror wall, past its east side, along the city's north edge into the next street east,
// down it and back to the start), sampled at `frames` frames along a closed smooth curve at
// constant speed. `cityScale` and `cityPath` are the city's (BuiltinSceneOptions). Throws
// std::invalid_argument for an unknown scene or frames < 1.
CameraPath makeBuiltinCameraPath(std::string_view scene, int frames = 360, double cityScale = 1.0,
                                 CityCameraPath cityPath = CityCameraPath::Street);

}  // namespace memograph::runtime
