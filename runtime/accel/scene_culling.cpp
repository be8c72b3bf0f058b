#include "runtime/accel/scene_culling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace memograph::runtime {

namespace {

// A grid finer than this over the scene is refused: its boxes would outnumber what they
// stand for.
constexpr std::uint64_t kMaxHitboxes = 65536;
constexpr std::uint32_t kMaxLowFrames = 1024;
// Activation needs at least this many hits however few rays a frame traces, so that in a
// small image (where the per-million thresholds stand for less than one hit) one stray
// diffuse ray does not switch a hitbox or an instance on. Counted rays, not counts: with
// sampled feedback each counted ray adds its weight (update() scales the minimum).
constexpr double kMinHitboxActivationHits = 4.0;
constexpr double kMinInstanceActivationHits = 2.0;

std::string number(double value) {
  std::string text = std::to_string(value);
  text.erase(text.find_last_not_of('0') + 1);
  if (!text.empty() && text.back() == '.')
    text.pop_back();
  return text;
}

Bounds transformed(const Bounds& box, const glm::mat4& m) {
  Bounds out{glm::vec3(std::numeric_limits<float>::max()),
             glm::vec3(-std::numeric_limits<float>::max())};
  for (int c = 0; c < 8; ++c) {
    glm::vec3 corner{c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                     c & 4 ? box.hi.z : box.lo.z};
    glm::vec3 p = glm::vec3(m * glm::vec4(corner, 1.0f));
    out.lo = glm::min(out.lo, p);
    out.hi = glm::max(out.hi, p);
  }
  return out;
}

float distanceTo(const Bounds& box, glm::vec3 p) {
  glm::vec3 d = glm::max(glm::max(box.lo - p, p - box.hi), glm::vec3(0.0f));
  return glm::length(d);
}

// Hits a threshold in hits per million rays stands for in a frame of `rays` rays.
double thresholdHits(double perMillion, std::uint64_t rays) {
  return perMillion * static_cast<double>(rays) * 1e-6;
}

}  // namespace

CullingMode parseCullingMode(std::string_view name) {
  if (name == "none")
    return CullingMode::None;
  if (name == "frustum")
    return CullingMode::Frustum;
  if (name == "lipac")
    return CullingMode::Lipac;
  throw std::invalid_argument("--culling takes none, frustum or lipac, not '" + std::string(name) +
                              "'");
}

std::string_view cullingModeName(CullingMode mode) {
  switch (mode) {
    case CullingMode::None:
      return "none";
    case CullingMode::Frustum:
      return "frustum";
    case CullingMode::Lipac:
      return "lipac";
  }
  return "none";
}

void validateCullingOptions(const CullingOptions& o) {
  auto positive = [](double value, const char* flag) {
    if (!(value > 0.0) || !std::isfinite(value))
      throw std::invalid_argument(std::string(flag) + " must be a positive number, not " +
                                  number(value));
  };
  auto within = [](std::uint32_t value, std::uint32_t low, std::uint32_t high, const char* flag) {
    if (value < low || value > high)
      throw std::invalid_argument(std::string(flag) + " must be in " + std::to_string(low) + ".." +
                                  std::to_string(high) + ", not " + std::to_string(value));
  };
  if (!(o.radius >= 0.0f) || !std::isfinite(o.radius))
    throw std::invalid_argument("--culling-radius must be 0 or more, not " + number(o.radius));
  positive(o.hitboxSize, "--hitbox-size");
  positive(o.hitboxActivate, "--hitbox-activate");
  positive(o.hitboxDeactivate, "--hitbox-deactivate");
  positive(o.instanceActivate, "--instance-activate");
  positive(o.instanceDeactivate, "--instance-deactivate");
  if (o.hitboxDeactivate >= o.hitboxActivate)
    throw std::invalid_argument("--hitbox-deactivate (" + number(o.hitboxDeactivate) +
                                ") must be below --hitbox-activate (" + number(o.hitboxActivate) +
                                "), or hitboxes switch on and off every frame");
  if (o.instanceDeactivate >= o.instanceActivate)
    throw std::invalid_argument("--instance-deactivate (" + number(o.instanceDeactivate) +
                                ") must be below --instance-activate (" +
                                number(o.instanceActivate) + ")");
  within(o.lowFrames, 1, kMaxLowFrames, "--low-frames");
  if (!(o.appearMinFraction >= 0.0f && o.appearMinFraction <= 1.0f))
    throw std::invalid_argument("the appearing instances' minimum size must be in [0, 1]");
  within(o.blasRebuildEvery, 1, kMaxLowFrames, "--blas-rebuild-every");
  if (o.lookAppearing == 0)
    throw std::invalid_argument("--look-appearing must be at least 1");
  within(o.feedbackStride, 1, 64, "--feedback-stride");
  within(o.feedbackPaths, 0, 64, "--feedback-paths");
  within(o.feedbackEvery, 1, 64, "--feedback-every");
  within(o.blasKeepFrames, 0, kMaxLowFrames, "--blas-keep-frames");
  if (!(o.lodPixelError > 0.0f && o.lodPixelError <= 1e6f))
    throw std::invalid_argument("--lod-pixel-error must be in (0, 1e6] pixels, not " +
                                number(o.lodPixelError));
  if (!(o.blasBuildMilliseconds >= 0.0 && o.blasBuildMilliseconds <= 1e6))
    throw std::invalid_argument("--blas-build-ms must be in [0, 1e6] milliseconds");
  if (o.mode == CullingMode::None &&
      (o.blasBudgetBytes || o.blasBuildTriangles || o.blasBuildMilliseconds > 0.0))
    throw std::invalid_argument(
        "--blas-budget, --blas-build-budget and --blas-build-ms manage the BLASes culling "
        "leaves out; they need --culling frustum or --culling lipac");
}

std::vector<Bounds> instanceBounds(const Scene& scene) {
  std::vector<Bounds> objectBounds;
  objectBounds.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes)
    objectBounds.push_back(meshBounds(mesh));
  std::vector<Bounds> out;
  out.reserve(scene.instances.size());
  for (const Instance& instance : scene.instances)
    out.push_back(transformed(objectBounds.at(instance.mesh), instance.objectToWorld));
  return out;
}

Frustum cameraFrustum(const Camera& camera, float aspect) {
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  float tanSide = tanHalf * aspect;
  // Each side plane holds the camera and one edge of the image: its inward normal is
  // perpendicular to the edge's direction (forward + tan * side) and points to the centre.
  glm::vec3 normals[5] = {
      glm::normalize(forward * tanSide - right), glm::normalize(forward * tanSide + right),
      glm::normalize(forward * tanHalf - up), glm::normalize(forward * tanHalf + up), forward};
  Frustum f;
  for (int i = 0; i < 5; ++i)
    f.planes[i] = glm::vec4(normals[i], -glm::dot(normals[i], camera.position));
  return f;
}

bool Frustum::intersects(const Bounds& box) const {
  // The box is outside when its corner farthest along a plane's normal is behind it.
  for (const glm::vec4& plane : planes) {
    glm::vec3 corner{plane.x >= 0.0f ? box.hi.x : box.lo.x, plane.y >= 0.0f ? box.hi.y : box.lo.y,
                     plane.z >= 0.0f ? box.hi.z : box.lo.z};
    if (glm::dot(glm::vec3(plane), corner) + plane.w < 0.0f)
      return false;
  }
  return true;
}

SceneCulling::SceneCulling(const Scene& scene, const CullingOptions& options)
    : options_(options), bounds_(instanceBounds(scene)) {
  validateCullingOptions(options_);
  const std::size_t n = scene.instances.size();
  std::vector<std::uint32_t> users(scene.meshes.size(), 0);
  for (const Instance& instance : scene.instances)
    ++users.at(instance.mesh);
  ownBlas_.resize(n);
  alwaysOn_.resize(n);
  states_.assign(
      n, options_.mode == CullingMode::None ? InstanceState::Active : InstanceState::Inactive);
  inFrustum_.assign(n, 0);
  appeared_.assign(n, 0);
  instanceWaits_.assign(n, DepartureWait{0, options_.lowFrames, 0});
  instanceHitbox_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    ownBlas_[i] = users[scene.instances[i].mesh] == 1;
    const glm::vec3 extent = bounds_[i].hi - bounds_[i].lo;
    alwaysOn_[i] = !scene.instances[i].castsShadow ||
                   std::max(extent.x, extent.z) > 2.0f * options_.hitboxSize;
  }
  if (options_.mode != CullingMode::Lipac || n == 0) {
    count();
    return;
  }

  // The hitbox grid over the instances' centres in x and z (§3.3.2: "a coarse spatial grid").
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Bounds& b : bounds_) {
    glm::vec3 c = b.centre();
    lo = glm::min(lo, glm::vec2(c.x, c.z));
    hi = glm::max(hi, glm::vec2(c.x, c.z));
  }
  const double size = options_.hitboxSize;
  const auto columns = static_cast<std::uint64_t>(std::floor((hi.x - lo.x) / size)) + 1;
  const auto rows = static_cast<std::uint64_t>(std::floor((hi.y - lo.y) / size)) + 1;
  if (columns * rows > kMaxHitboxes)
    throw std::invalid_argument("--hitbox-size " + number(size) + " makes " +
                                std::to_string(columns) + " x " + std::to_string(rows) +
                                " hitboxes over this scene (at most " +
                                std::to_string(kMaxHitboxes) + "); choose a larger size");
  const std::size_t cells = static_cast<std::size_t>(columns * rows);
  hitboxInstances_.resize(cells);
  hitboxBounds_.assign(cells, Bounds{glm::vec3(std::numeric_limits<float>::max()),
                                     glm::vec3(-std::numeric_limits<float>::max())});
  for (std::size_t i = 0; i < n; ++i) {
    if (alwaysOn_[i])
      continue;
    glm::vec3 c = bounds_[i].centre();
    auto column = std::min<std::uint64_t>(columns - 1, std::uint64_t((c.x - lo.x) / size));
    auto row = std::min<std::uint64_t>(rows - 1, std::uint64_t((c.z - lo.y) / size));
    auto h = static_cast<std::uint32_t>(row * columns + column);
    instanceHitbox_[i] = h;
    hitboxInstances_[h].push_back(static_cast<std::uint32_t>(i));
    // The box covers its instances whole, so every ray towards one of them crosses it.
    hitboxBounds_[h].lo = glm::min(hitboxBounds_[h].lo, bounds_[i].lo);
    hitboxBounds_[h].hi = glm::max(hitboxBounds_[h].hi, bounds_[i].hi);
  }
  hitboxActive_.assign(cells, 0);
  hitboxWaits_.assign(cells, DepartureWait{0, options_.lowFrames, 0});
  count();
}

void SceneCulling::setState(std::uint32_t instance, InstanceState state) {
  if (states_[instance] != state) {
    states_[instance] = state;
    ++counts_.changes;
  }
}

bool SceneCulling::countInFrame(DepartureWait& wait, bool low) const {
  if (!low) {
    wait.lowFrames = 0;
    countSettledFrame(wait);
    return false;
  }
  wait.settledFrames = 0;  // a low frame ends the run that halves the wait
  if (++wait.lowFrames < wait.neededFrames)
    return false;
  wait.lowFrames = 0;
  wait.neededFrames = std::min(longestWait(), 2 * wait.neededFrames);
  return true;
}

void SceneCulling::countSettledFrame(DepartureWait& wait) const {
  if (wait.neededFrames <= options_.lowFrames)
    return;
  if (++wait.settledFrames < longestWait())
    return;
  wait.neededFrames = std::max(options_.lowFrames, wait.neededFrames / 2);
  wait.settledFrames = 0;
}

bool SceneCulling::appearsLarge(std::uint32_t instance, const Camera& camera) const {
  const float minAngle = options_.appearMinFraction * glm::radians(camera.verticalFovDegrees);
  const Bounds& b = bounds_[instance];
  const float radius = 0.5f * glm::length(b.hi - b.lo);
  const float distance = glm::length(b.centre() - camera.position);
  return distance <= radius || std::asin(radius / distance) >= minAngle;
}

bool SceneCulling::wantsLook(const Camera& camera, float aspect) const {
  if (options_.mode != CullingMode::Lipac || hitboxActive_.empty())
    return false;
  if (first_)
    return true;
  const Frustum frustum = cameraFrustum(camera, aspect);
  std::uint32_t appearing = 0;
  for (std::uint32_t i = 0; i < instanceCount(); ++i) {
    if (alwaysOn_[i] || !ownBlas_[i] || inFrustum_[i] || states_[i] == InstanceState::Active ||
        !frustum.intersects(bounds_[i]) || !appearsLarge(i, camera))
      continue;
    if (++appearing >= options_.lookAppearing)
      return true;
  }
  return false;
}

void SceneCulling::look(const Camera& camera, float aspect) {
  counts_.changes = 0;
  const Frustum frustum = cameraFrustum(camera, aspect);
  std::vector<std::uint8_t> opened(hitboxCount(), 0);
  for (std::uint32_t h = 0; h < hitboxCount(); ++h) {
    if (hitboxActive_[h] || hitboxInstances_[h].empty() || !frustum.intersects(hitboxBounds_[h]))
      continue;
    hitboxActive_[h] = 1;
    hitboxWaits_[h].lowFrames = 0;
    opened[h] = 1;
  }
  for (std::uint32_t i = 0; i < instanceCount(); ++i) {
    // Seen in this frustum now: update() will not count it as appearing.
    inFrustum_[i] = frustum.intersects(bounds_[i]);
    if (alwaysOn_[i]) {
      setState(i, InstanceState::Active);
      continue;
    }
    // Instances of hitboxes already active, or still inactive, keep their states (one that
    // appeared stays while it is hit).
    if (opened[instanceHitbox_[i]]) {
      instanceWaits_[i].lowFrames = 0;
      appeared_[i] = 0;
      setState(i, ownBlas_[i] ? InstanceState::Omitted : InstanceState::Active);
    }
  }
  first_ = false;
  count();
}

void SceneCulling::update(const Camera& camera, float aspect, std::span<const std::uint32_t> hits,
                          std::uint64_t rays, double rayWeight) {
  counts_.changes = 0;
  const Frustum frustum = cameraFrustum(camera, aspect);
  switch (options_.mode) {
    case CullingMode::None:
      break;
    case CullingMode::Frustum:
      updateFrustum(frustum, camera);
      break;
    case CullingMode::Lipac:
      updateLipac(frustum, camera, hits, rays, rayWeight > 0.0 ? rayWeight : 1.0);
      break;
  }
  first_ = false;
  count();
}

void SceneCulling::updateFrustum(const Frustum& frustum, const Camera& camera) {
  for (std::uint32_t i = 0; i < instanceCount(); ++i) {
    bool keep = alwaysOn_[i] || frustum.intersects(bounds_[i]) ||
                distanceTo(bounds_[i], camera.position) <= options_.radius;
    setState(i, keep ? InstanceState::Active : InstanceState::Inactive);
  }
}

void SceneCulling::updateLipac(const Frustum& frustum, const Camera& camera,
                               std::span<const std::uint32_t> hits, std::uint64_t rays,
                               double rayWeight) {
  const std::uint32_t n = instanceCount();
  if (!hits.empty() && hits.size() != counterCount())
    throw std::logic_error("SceneCulling::update: " + std::to_string(hits.size()) +
                           " hit counters for " + std::to_string(counterCount()) + " slots");
  if (!hits.empty()) {
    // Hitboxes (§3.3.2, algorithm 5): an inactive one counts the rays through its box, an
    // active one the hits of its instances (their own, or their boxes' while omitted).
    // A counted ray adds rayWeight to its counter (sampled feedback; 1 in a look's probe, and
    // a sparse look passes less, update()): the minimums are in rays, so they scale with it;
    // the per-million thresholds keep their expected value.
    const double activate = std::max(kMinHitboxActivationHits * rayWeight,
                                     thresholdHits(options_.hitboxActivate, rays));
    const double deactivate = thresholdHits(options_.hitboxDeactivate, rays);
    for (std::uint32_t h = 0; h < hitboxCount(); ++h) {
      if (hitboxInstances_[h].empty())
        continue;
      std::uint64_t sum = 0;
      if (hitboxActive_[h]) {
        for (std::uint32_t i : hitboxInstances_[h])
          sum += hits[i];
        if (countInFrame(hitboxWaits_[h], double(sum) < deactivate))
          hitboxActive_[h] = 0;
      } else {
        countSettledFrame(hitboxWaits_[h]);
        sum = hits[n + h];
        for (std::uint32_t i : hitboxInstances_[h])
          sum += hits[i];  // instances activated on their own (appearing) count too
        if (double(sum) >= activate) {
          hitboxActive_[h] = 1;
          hitboxWaits_[h].lowFrames = 0;
        }
      }
    }
    // Instances (algorithm 5's third pass).
    const double instanceActivate = std::max(kMinInstanceActivationHits * rayWeight,
                                             thresholdHits(options_.instanceActivate, rays));
    const double instanceDeactivate = thresholdHits(options_.instanceDeactivate, rays);
    for (std::uint32_t i = 0; i < n; ++i) {
      if (alwaysOn_[i])
        continue;
      const double c = hits[i];
      const bool low = c < instanceDeactivate;
      const InstanceState state = states_[i];
      DepartureWait& wait = instanceWaits_[i];
      if (!hitboxActive_[instanceHitbox_[i]]) {
        // Only an instance activated on its own (it appeared) stays, while it is hit; low
        // for long enough, it leaves (and waits longer next time).
        if (appeared_[i] && state == InstanceState::Active) {
          if (!countInFrame(wait, low))
            continue;
        } else {
          countSettledFrame(wait);
        }
        appeared_[i] = 0;
        setState(i, InstanceState::Inactive);
        continue;
      }
      appeared_[i] = 0;
      if (!ownBlas_[i]) {
        wait.lowFrames = 0;
        countSettledFrame(wait);
        setState(i, InstanceState::Active);  // its BLAS is shared: cheap to include
      } else if (state == InstanceState::Inactive) {
        countSettledFrame(wait);
        setState(i, InstanceState::Omitted);
      } else if (state == InstanceState::Omitted) {
        countSettledFrame(wait);
        if (c >= instanceActivate) {
          wait.lowFrames = 0;
          setState(i, InstanceState::Active);
        }
      } else if (countInFrame(wait, low)) {
        setState(i, InstanceState::Omitted);
      }
    }
  }
  // Instances that enter the frustum large enough to be seen at once are activated now
  // (§3.3.2: the feedback would show them a frame or more late).
  for (std::uint32_t i = 0; i < n; ++i) {
    if (alwaysOn_[i]) {
      setState(i, InstanceState::Active);
      continue;
    }
    const bool inside = frustum.intersects(bounds_[i]);
    const bool appeared = inside && (first_ || !inFrustum_[i]);
    inFrustum_[i] = inside;
    if (!appeared || states_[i] == InstanceState::Active)
      continue;
    if (appearsLarge(i, camera)) {
      instanceWaits_[i].lowFrames = 0;
      appeared_[i] = hitboxActive_.empty() || !hitboxActive_[instanceHitbox_[i]];
      setState(i, InstanceState::Active);
    }
  }
}

void SceneCulling::count() {
  const std::uint32_t changes = counts_.changes;
  counts_ = {};
  counts_.changes = changes;
  for (InstanceState s : states_) {
    counts_.active += s == InstanceState::Active;
    counts_.omitted += s == InstanceState::Omitted;
    counts_.inactive += s == InstanceState::Inactive;
  }
  for (std::uint32_t h = 0; h < hitboxCount(); ++h) {
    if (hitboxInstances_[h].empty())
      continue;
    ++counts_.hitboxes;
    counts_.activeHitboxes += hitboxActive_[h] != 0;
  }
}

}  // namespace memograph::runtime
