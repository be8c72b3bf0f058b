// Which LOD of its mesh each instance shows (seeds/001 §3.3.1: a BLAS per mesh LOD): the
// coarsest whose error, in world units, stays within `pixelError` footprints at the instance:
// the simplifier's, or the length of a part the level removes whole where that is more. The
// footprint is the narrowest ray cone a counted ray brought to the instance in the last counting
// frames (LiPaC's feedback, hit_feedback.glsl bufferHitFootprint), at most a pixel's width at its
// distance from the camera (all there is for one no counted ray hit). Distance alone fails under
// magnification (§3.1.1: "curved mirrors that can significantly magnify objects in the distance"):
// a curved mirror narrows the cones that reach a far object below its distance's pixel, and what
// the cone feedback measures there keeps it detailed. Host-side state only, no Vulkan, so it is
// tested without a device.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

// Footprint slots with no counted hit (the feedback buffer's clear value).
inline constexpr std::uint32_t kNoFootprint = 0xFFFFFFFFu;

// The angle one pixel spans at the image's centre (the primary cone's spread,
// frame_loop.cpp's cameraPosition.w).
float pixelSpreadAngle(const Camera& camera, std::uint32_t imageHeight);

// The coarsest level whose error is at most pixelError * footprint: 0 (the mesh itself) or
// l for levelErrors[l - 1] (world units, increasing). A footprint that is not a positive
// finite number gets level 0.
std::uint32_t lodForFootprint(std::span<const float> levelErrors, float footprint,
                              float pixelError);

class InstanceLodChoice {
 public:
  // `bounds`: each instance's world bounds (SceneCulling::bounds). Instances whose mesh has
  // LODs (Scene::meshLods) and that cast shadows (a light's quad is never simplified) get a
  // choice; the others stay at level 0.
  InstanceLodChoice(const Scene& scene, const std::vector<Bounds>& bounds, float pixelError);

  // Before a frame: `footprints`, one per instance, a counted hit's narrowest cone width as
  // float bits (kNoFootprint: none), from the last counting frame (empty: no feedback). An
  // instance's footprint is the narrowest cone the feedback brought it in this and the last
  // kFeedbackMemory updates (sampled feedback, 1 of P paths and 1 in N pixel blocks, counts
  // the narrowest only now and then), but never wider than a pixel at its
  // distance: a wide cone (a diffuse bounce's) reaches an instance that the camera also sees
  // beside it, or whose shadow it sees, at the camera's pixels. So feedback only makes an
  // instance finer than its distance would (a mirror's magnification, seeds/001 §3.1.1).
  // After its first choice, a coarser level than the one chosen last needs its error within
  // the footprint by kCoarserMargin, so that a footprint that wavers near a level's edge does
  // not switch (and build) back and forth; a finer one is taken at once.
  void update(const Camera& camera, float pixelSpreadAngle,
              std::span<const std::uint32_t> footprints);

  // The level each instance wants (its BLAS may still be waiting for a build).
  const std::vector<std::uint8_t>& wanted() const { return wanted_; }
  std::uint32_t levelCount(std::uint32_t instance) const;
  // Whether the last update took the instance's footprint from the feedback (narrower than
  // its distance's pixel).
  bool fromFeedback(std::uint32_t instance) const { return fromFeedback_[instance] != 0; }

  static constexpr float kCoarserMargin = 1.25f;
  static constexpr std::uint8_t kFeedbackMemory = 4;

 private:
  float pixelError_;
  std::vector<Bounds> bounds_;
  std::vector<std::vector<float>> meshErrors_;  // per mesh: its levels' object-space errors
  std::vector<std::uint32_t> instanceMesh_;
  std::vector<float> instanceScale_;  // the largest axis scale of the instance's transform
  std::vector<std::uint8_t> eligible_;
  std::vector<std::uint8_t> wanted_;
  std::vector<std::uint8_t> fromFeedback_;
  std::vector<float> feedbackFootprint_;   // the narrowest recent cone (see update)
  std::vector<std::uint8_t> feedbackAge_;  // updates since feedbackFootprint_ was set
  std::vector<std::uint8_t> chosen_;       // a level was chosen (the margin holds from then on)
  std::vector<float> worldErrors_;         // scratch: one instance's levels in world units
};

}  // namespace memograph::runtime
