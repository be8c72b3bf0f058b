// `--debug-culling`: a top-down view of a culled render's last frame (as seeds/001 Fig. 3.3
// shows the TLAS's state): each instance's footprint in x and z coloured by its state
// (larger footprints under smaller ones; none over half the view, i.e. the ground),
// LiPaC's inactive hitboxes outlined, the camera as a dot with its view direction; with mesh
// LODs an active instance's colour tells the LOD its BLAS has (seeds/001 §3.3.1).
#pragma once

#include <cstdint>
#include <span>

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
// Active instances by the LOD in the TLAS: 0 (the mesh itself) kViewActive's orange, then
// green, cyan, blue and violet for LOD 1, 2, 3 and 4 or coarser, away from the red-yellow
// of the states (the first LOD whose colour the other states do not use).
inline constexpr float kViewLods[4][3] = {
    {0.2f, 0.8f, 0.2f}, {0.1f, 0.75f, 0.8f}, {0.25f, 0.35f, 1.0f}, {0.7f, 0.3f, 0.9f}};

// A `size` x `size` image of the whole scene seen from above. `lods`: each instance's LOD in
// the TLAS (empty: every active instance orange).
HdrImage cullingTopView(const SceneCulling& culling, const Camera& camera, std::uint32_t size,
                        std::span<const std::uint8_t> lods = {});

}  // namespace memograph::runtime
