// `--debug-culling`: a top-down view of a culled render's last frame (as seeds/001 Fig. 3.3
// shows the TLAS's state): each instance's footprint in x and z coloured by its state
// (larger footprints under smaller ones; none over half the view, i.e. the ground),
// LiPaC's inactive hitboxes outlined, the camera as a dot with its view direction.
#pragma once

#include <cstdint>

#include "runtime/accel/scene_culling.h"
#include "runtime/host/image.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

// Colours (linear RGB): active instances orange, omitted yellow, inactive dark grey,
// inactive hitboxes' outlines blue, the camera red; the background black. North (-z) up.
inline constexpr float kViewActive[3] = {0.95f, 0.35f, 0.05f};
inline constexpr float kViewOmitted[3] = {0.9f, 0.85f, 0.1f};
inline constexpr float kViewInactive[3] = {0.12f, 0.12f, 0.12f};
inline constexpr float kViewHitbox[3] = {0.1f, 0.3f, 0.9f};
inline constexpr float kViewCamera[3] = {1.0f, 0.0f, 0.0f};

// A `size` x `size` image of the whole scene seen from above.
HdrImage cullingTopView(const SceneCulling& culling, const Camera& camera, std::uint32_t size);

}  // namespace memograph::runtime
