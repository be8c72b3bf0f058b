#include "runtime/accel/culling_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace memograph::runtime {

namespace {

struct TopView {
  HdrImage image;
  glm::vec2 lo{0.0f};
  float scale = 1.0f;  // pixels per scene unit

  glm::vec2 toPixel(float x, float z) const { return (glm::vec2(x, z) - lo) * scale; }

  void set(int x, int y, const float colour[3]) {
    if (x < 0 || y < 0 || x >= int(image.width) || y >= int(image.height))
      return;
    float* p = image.pixel(std::uint32_t(x), std::uint32_t(y));
    p[0] = colour[0];
    p[1] = colour[1];
    p[2] = colour[2];
    p[3] = 1.0f;
  }

  // A footprint: at least one pixel, so a small instance still shows.
  void fill(const Bounds& b, const float colour[3]) {
    glm::vec2 a = toPixel(b.lo.x, b.lo.z), c = toPixel(b.hi.x, b.hi.z);
    for (int y = int(std::floor(a.y)); y <= std::max(int(std::floor(a.y)), int(c.y)); ++y)
      for (int x = int(std::floor(a.x)); x <= std::max(int(std::floor(a.x)), int(c.x)); ++x)
        set(x, y, colour);
  }

  void outline(const Bounds& b, const float colour[3]) {
    glm::vec2 a = toPixel(b.lo.x, b.lo.z), c = toPixel(b.hi.x, b.hi.z);
    for (int x = int(a.x); x <= int(c.x); ++x) {
      set(x, int(a.y), colour);
      set(x, int(c.y), colour);
    }
    for (int y = int(a.y); y <= int(c.y); ++y) {
      set(int(a.x), y, colour);
      set(int(c.x), y, colour);
    }
  }
};

}  // namespace

HdrImage cullingTopView(const SceneCulling& culling, const Camera& camera, std::uint32_t size,
                        std::span<const std::uint8_t> lods) {
  TopView view;
  view.image.width = view.image.height = size;
  view.image.rgba.assign(std::size_t(size) * size * 4, 0.0f);
  for (std::size_t i = 3; i < view.image.rgba.size(); i += 4)
    view.image.rgba[i] = 1.0f;
  // The view spans the camera and the instances' centres (not the ground's edges).
  const auto& bounds = culling.bounds();
  glm::vec2 lo(camera.position.x, camera.position.z), hi = lo;
  for (const Bounds& b : bounds) {
    const glm::vec3 c = b.centre();
    lo = glm::min(lo, glm::vec2(c.x, c.z));
    hi = glm::max(hi, glm::vec2(c.x, c.z));
  }
  const float extent = std::max({hi.x - lo.x, hi.y - lo.y, 1e-3f}) * 1.1f;
  view.lo = 0.5f * (lo + hi) - glm::vec2(0.5f * extent);
  view.scale = float(size - 1) / extent;

  // The largest footprints first, so that what stands on a slab shows; footprints over a
  // half of the view (the ground, never culled) are left out: they would cover the rest.
  std::vector<std::uint32_t> order;
  auto area = [&](std::uint32_t i) {
    return (bounds[i].hi.x - bounds[i].lo.x) * (bounds[i].hi.z - bounds[i].lo.z);
  };
  for (std::uint32_t i = 0; i < bounds.size(); ++i)
    if (area(i) <= 0.5f * extent * extent)
      order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return area(a) > area(b); });
  const auto& states = culling.states();
  for (std::uint32_t i : order) {
    const float* colour = states[i] == InstanceState::Active    ? kViewActive
                          : states[i] == InstanceState::Omitted ? kViewOmitted
                                                                : kViewInactive;
    if (states[i] == InstanceState::Active && i < lods.size() && lods[i] > 0)
      colour = kViewLods[std::min<std::size_t>(lods[i], std::size(kViewLods)) - 1];
    const float edge[3] = {0.5f * colour[0], 0.5f * colour[1], 0.5f * colour[2]};
    view.fill(bounds[i], colour);
    view.outline(bounds[i], edge);  // tells an instance from the slab it stands on
  }
  for (std::uint32_t h = 0; h < culling.hitboxCount(); ++h)
    if (culling.hitboxUsed(h) && !culling.hitboxActive(h))
      view.outline(culling.hitboxBounds(h), kViewHitbox);

  // The camera: a dot and a line along its view direction.
  glm::vec2 c = view.toPixel(camera.position.x, camera.position.z);
  glm::vec3 forward = camera.target - camera.position;
  glm::vec2 d(forward.x, forward.z);
  d = glm::length(d) > 1e-6f ? glm::normalize(d) : glm::vec2(0.0f);
  for (int y = -2; y <= 2; ++y)
    for (int x = -2; x <= 2; ++x)
      view.set(int(c.x) + x, int(c.y) + y, kViewCamera);
  for (int t = 0; t < int(size / 16); ++t)
    view.set(int(c.x + d.x * float(t)), int(c.y + d.y * float(t)), kViewCamera);
  return view.image;
}

}  // namespace memograph::runtime
