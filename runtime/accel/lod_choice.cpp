#include "runtime/accel/lod_choice.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace memograph::runtime {

namespace {

float distanceTo(const Bounds& box, glm::vec3 p) {
  const glm::vec3 d = glm::max(glm::max(box.lo - p, p - box.hi), glm::vec3(0.0f));
  return glm::length(d);
}

// How much the transform stretches object-space lengths at most: a bound on a world-space
// error from an object-space one.
float largestScale(const glm::mat4& m) {
  return std::max(
      {glm::length(glm::vec3(m[0])), glm::length(glm::vec3(m[1])), glm::length(glm::vec3(m[2]))});
}

}  // namespace

float pixelSpreadAngle(const Camera& camera, std::uint32_t imageHeight) {
  const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  return std::atan(2.0f * tanHalf / float(std::max(imageHeight, 1u)));
}

std::uint32_t lodForFootprint(std::span<const float> levelErrors, float footprint,
                              float pixelError) {
  if (!(footprint > 0.0f) || !std::isfinite(footprint) || !(pixelError > 0.0f))
    return 0;
  const float allowed = pixelError * footprint;
  std::uint32_t level = 0;
  for (std::size_t l = 0; l < levelErrors.size(); ++l)
    if (levelErrors[l] <= allowed)
      level = static_cast<std::uint32_t>(l + 1);
  return level;
}

InstanceLodChoice::InstanceLodChoice(const Scene& scene, const std::vector<Bounds>& bounds,
                                     float pixelError)
    : pixelError_(pixelError), bounds_(bounds) {
  if (!(pixelError > 0.0f) || !std::isfinite(pixelError))
    throw std::invalid_argument("--lod-pixel-error must be a positive number");
  if (bounds.size() != scene.instances.size())
    throw std::logic_error("InstanceLodChoice: " + std::to_string(bounds.size()) + " bounds for " +
                           std::to_string(scene.instances.size()) + " instances");
  meshErrors_.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshLods.size() && m < scene.meshes.size(); ++m)
    for (const MeshLod& lod : scene.meshLods[m])
      // What a viewer may see change: the surface moved, or a part gone whole (its length).
      meshErrors_[m].push_back(std::max(lod.error, lod.removedPart));
  const std::size_t n = scene.instances.size();
  instanceMesh_.resize(n);
  instanceScale_.resize(n);
  eligible_.resize(n);
  wanted_.assign(n, 0);
  fromFeedback_.assign(n, 0);
  feedbackFootprint_.assign(n, 0.0f);
  feedbackAge_.assign(n, kFeedbackMemory + 1);  // nothing remembered
  chosen_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Instance& instance = scene.instances[i];
    instanceMesh_[i] = instance.mesh;
    instanceScale_[i] = largestScale(instance.objectToWorld);
    eligible_[i] = instance.castsShadow && instance.mesh < meshErrors_.size() &&
                   !meshErrors_[instance.mesh].empty() && std::isfinite(instanceScale_[i]);
  }
}

std::uint32_t InstanceLodChoice::levelCount(std::uint32_t instance) const {
  return eligible_[instance]
             ? static_cast<std::uint32_t>(meshErrors_[instanceMesh_[instance]].size()) + 1
             : 1;
}

void InstanceLodChoice::update(const Camera& camera, float pixelSpreadAngle,
                               std::span<const std::uint32_t> footprints) {
  if (!footprints.empty() && footprints.size() != wanted_.size())
    throw std::logic_error("InstanceLodChoice::update: " + std::to_string(footprints.size()) +
                           " footprints for " + std::to_string(wanted_.size()) + " instances");
  for (std::size_t i = 0; i < wanted_.size(); ++i) {
    fromFeedback_[i] = 0;
    if (!eligible_[i])
      continue;
    // The narrowest cone of this and the last kFeedbackMemory updates: sampled feedback (1 of
    // P paths, 1 in N pixel blocks) brings the narrowest cones, a mirror's, only now and then.
    if (feedbackAge_[i] <= kFeedbackMemory)
      ++feedbackAge_[i];
    if (!footprints.empty() && footprints[i] != kNoFootprint) {
      float counted = 0.0f;
      std::memcpy(&counted, &footprints[i], sizeof counted);
      if (!(counted >= 0.0f) || !std::isfinite(counted))
        counted = 0.0f;  // bits the shader never writes: the finest level, to be safe
      if (feedbackAge_[i] > kFeedbackMemory || counted < feedbackFootprint_[i]) {
        feedbackFootprint_[i] = counted;
        feedbackAge_[i] = 0;
      }
    }
    // A pixel's width at the nearest point of the instance (0 inside it: the finest), which
    // also bounds what the feedback brings: a wide cone (a diffuse bounce's) reaches what the
    // camera sees beside it, and what casts the shadows the camera sees, whose outlines are
    // seen at the camera's pixels, not the bounce's.
    float footprint = distanceTo(bounds_[i], camera.position) * pixelSpreadAngle;
    if (feedbackAge_[i] <= kFeedbackMemory && feedbackFootprint_[i] < footprint) {
      footprint = feedbackFootprint_[i];
      fromFeedback_[i] = 1;
    }
    worldErrors_.clear();
    for (const float e : meshErrors_[instanceMesh_[i]])
      worldErrors_.push_back(e * instanceScale_[i]);
    const std::uint32_t level = lodForFootprint(worldErrors_, footprint, pixelError_);
    if (level > wanted_[i] && chosen_[i])
      wanted_[i] = static_cast<std::uint8_t>(std::max<std::uint32_t>(
          wanted_[i], lodForFootprint(worldErrors_, footprint / kCoarserMargin, pixelError_)));
    else
      wanted_[i] = static_cast<std::uint8_t>(level);
    chosen_[i] = 1;
  }
}

}  // namespace memograph::runtime
