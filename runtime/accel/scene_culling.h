// Which instances go into the TLAS each frame (seeds/001 §3.3.2): all of them, those in the
// camera's frustum or near it, or light-path-guided culling (LiPaC), where hit counters from
// the last frame's trace decide. Host-side state only, no Vulkan, so it is tested without a
// device; the renderer feeds it the hit counters and builds the TLAS from its states.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

enum class CullingMode { None, Frustum, Lipac };

// Throws std::invalid_argument listing the names on anything else.
CullingMode parseCullingMode(std::string_view name);
std::string_view cullingModeName(CullingMode mode);

struct CullingOptions {
  CullingMode mode = CullingMode::None;
  // frustum: instances within this distance of the camera stay too (shadows and reflections
  // of what is just behind it), in scene units (metres in the built-in scenes).
  float radius = 30.0f;
  // lipac: the hitbox grid's cell edge in x and z.
  float hitboxSize = 50.0f;
  // lipac thresholds, in hits per million rays traced in the frame, so that one setting
  // holds at every image size and sample count (activation takes at least 4 hits for a
  // hitbox, 2 for an instance, however small the frame). Deactivation waits `lowFrames`
  // counting frames (feedbackEvery): doubled for a hitbox or an instance each time it leaves,
  // up to kDepartureWaitMaxDoublings doublings, and halved back after each run of that many
  // (16 x lowFrames) counting frames without a low one (DepartureWait).
  // ϑ_a activates an inactive hitbox (its box's hits plus its instances'); an active one
  // deactivates after `lowFrames` counting frames in a row below ϑ_d (§3.3.2: "around factor
  // 10" apart, "low for several frames").
  double hitboxActivate = 20.0;
  double hitboxDeactivate = 2.0;
  // An instance with its own BLAS (used by no other instance) in an active hitbox is first
  // omitted (a box counts its rays) and activated above σ_a; an active one goes back to
  // omitted after `lowFrames` counting frames below σ_o.
  // The defaults of σ_a, σ_o, lowFrames and the feedback's sampling (feedbackStride,
  // feedbackPaths, feedbackEvery) are the H200's best measured on the city's street path
  // (docs/design/culling.md, "Measuring on the GPU machine": every 5th camera of the whole path,
  // peak AS 0.25x the unculled scene's, the whole path's time 1.005x, the frames that do not count
  // 0.98x; counting every frame in 1 block of 4 at σ_a = 16: 0.30x and the path's 1.13x).
  double instanceActivate = 16.0;
  double instanceDeactivate = 1.6;
  std::uint32_t lowFrames = 2;
  // An instance that enters the frustum is activated at once when its bounding sphere's
  // angular radius is at least this fraction of the vertical field of view (§3.3.2: the
  // feedback's latency would show it a frame late); smaller ones wait for the feedback.
  float appearMinFraction = 0.01f;
  // BLAS residency (§3.3.1): bytes of resident BLASes past which those no instance in the
  // TLAS uses are evicted, least recently used first (0: no limit), and the triangles built
  // per frame at most (0: no limit; at least one BLAS is built per frame): the same inputs
  // build the same BLASes, so give the same pictures, on any machine.
  std::uint64_t blasBudgetBytes = 0;
  std::uint64_t blasBuildTriangles = 0;
  // And the GPU milliseconds of a frame's BLAS builds at most (0: no limit; §3.3.1's time
  // budget), at the build rate the timestamps of the builds so far measured; the set built
  // then depends on the machine's speed, where the triangle budget's does not.
  double blasBuildMilliseconds = 0.0;
  // A BLAS no instance in the TLAS has used for more than this many frames is evicted
  // whatever the budget (§3.3.1: "or when they have not been used for many frames"), so
  // the resident set follows what the frames keep; 0: only the budget evicts.
  std::uint32_t blasKeepFrames = 2;
  // Animated meshes' BLASes: updated in place every frame, rebuilt every this many frames
  // (refits loosen the tree; §3.3.1). 1: rebuilt every frame.
  std::uint32_t blasRebuildEvery = 16;
  // lipac: 1 in this many 8×8-pixel blocks counts its rays in a counting frame (other
  // blocks the next), each count weighted by it: the counters keep their expected value
  // (thresholds are per million rays of the frame) while the counting-box probes, a second
  // trace per ray, cost 1/N. 1: every block counts.
  std::uint32_t feedbackStride = 1;
  // lipac: N of each pixel's P paths count their rays in a counting frame (other paths the
  // next), weighted P / N, so N divides P (the renderer checks); 0, or N >= P: every path.
  // Unlike the blocks every pixel still counts, so an instance seen in a few pixels is seen
  // every counting frame, while the probes cost N / P. With N < P a counting frame traces the
  // P - N paths that do not count with the pipeline compiled without the feedback, then the N
  // that do with it, in dispatches of their own (planPathDispatches), so that only those run
  // the feedback's code (its probes' trace call and counters, which slow a pipeline whether a
  // path counts or not): on the H200 its counting frames took 0.940x the unculled frame's
  // time against 1.119x in one dispatch, on an H100 0.939x against 1.128x (docs/design/culling.md,
  // "Split counting frames").
  std::uint32_t feedbackPaths = 1;
  // lipac: the trace counts every this many frames (frames 0, N, 2N, ...); the frames between
  // trace with a pipeline compiled without the feedback (its probes, and its code), and their
  // updates only activate what appears in the frustum. `lowFrames` counts counting frames
  // (the default 2 at N = 4 waits 8 frames). On the H200 a frame without the feedback took
  // 0.98x the unculled frame's time, one with it 1.09x with one path of 6 counted and 1.19x
  // with every path (docs/design/culling.md). N = 8 (with lowFrames 1) was faster on an H100 only
  // by frames whose stale states lacked what their paths hit (rays down to 0.58x none's at
  // stride 5). 1: every frame counts.
  std::uint32_t feedbackEvery = 4;
  // lipac: looks (SceneCulling::look): before the first frame, and before a frame whose
  // frustum brings at least `lookAppearing` instances with their own BLAS into view at once, a
  // probe trace of its camera decides which of them it needs, rather than activating every
  // instance that appears large in the frustum, hidden ones too (the whole city from a path
  // that flies in or turns towards it).
  std::uint32_t lookAppearing = 8;
  // Mesh LODs (seeds/001 §3.1.1, §3.3.1; Scene::meshLods, docs/design/culling.md "Mesh LODs"):
  // in a culled render an instance in the TLAS shows the coarsest LOD of its mesh whose error
  // stays within `lodPixelError` footprints of the narrowest ray cone that reached it in the
  // recent counting frames, at most a pixel at its distance (InstanceLodChoice). Each (mesh,
  // LOD) has one BLAS, shared, built under the build budgets like any other. Off by default:
  // on lavapipe (the small city) no setting met both targets: at lodPixelError 1 LiPaC's peak
  // AS memory was 0.80x the unculled scene's (street path) and the mirror view (32 frames) differed
  // from the unculled one by a mean LDR-FLIP of 0.0065; at 0.25 the FLIP was 0.0049 at 1.01x. The
  // GPU run (docs/design/culling.md) decides. No effect without culling, nor on a scene without
  // LODs.
  bool meshLods = false;
  float lodPixelError = 1.0f;
  // Whether a render shows LODs: culled, with meshLods (what a built-in scene then builds).
  bool showsMeshLods() const { return mode != CullingMode::None && meshLods; }
  // The render's image height, for a pixel's angle (the renderer sets it; 0: 1080).
  std::uint32_t imageHeight = 0;
};

// Throws std::invalid_argument with the option's flag name on a bad value.
void validateCullingOptions(const CullingOptions& options);

enum class InstanceState : std::uint8_t { Inactive = 0, Omitted = 1, Active = 2 };

// A departure doubles the wait of a hitbox or an instance at most this many times: it never
// exceeds 16 x CullingOptions::lowFrames counting frames (the default 2 at --feedback-every 4:
// 32 counting frames, 128 frames).
inline constexpr std::uint32_t kDepartureWaitMaxDoublings = 4;

// How long a hitbox or an instance in the TLAS counts low before it leaves. §3.3.2 deactivates
// "only after the number of hits has been low for several frames" and puts the thresholds
// "around factor 10" apart "to avoid frequent state cycles". A small frame still cycled (its
// few hits straddle the thresholds), so each departure doubles the wait: what cycles stays
// longer each time. Several frames, not thousands: the doubling stops at
// kDepartureWaitMaxDoublings, and the wait halves back towards `lowFrames` after each run of
// as many counting frames as the longest wait without a low one (the hitbox or instance was
// out, or in with enough hits), so one that stops cycling leaves as fast as a new one again.
// A low frame ends the run, so what is in and straddles its threshold keeps its wait; a run
// as long as the longest wait, not the current one, so what comes back after staying out for
// a few frames, a slower cycle, keeps it too (with a run of the current wait the small city's
// static camera never settled).
struct DepartureWait {
  std::uint32_t lowFrames = 0;      // counting frames in a row below its deactivation threshold
  std::uint32_t neededFrames = 0;   // low frames after which it leaves
  std::uint32_t settledFrames = 0;  // counting frames in a row without a low one
};

// World-space bounds of every instance of the scene.
std::vector<Bounds> instanceBounds(const Scene& scene);

// The five planes of a camera's frustum (inward normals, w = offset): four sides and the
// camera's own plane; no far plane.
struct Frustum {
  glm::vec4 planes[5];
  bool intersects(const Bounds& box) const;
};
Frustum cameraFrustum(const Camera& camera, float aspect);

struct CullingCounts {
  std::uint32_t active = 0;
  std::uint32_t omitted = 0;
  std::uint32_t inactive = 0;
  std::uint32_t hitboxes = 0;        // hitboxes with instances
  std::uint32_t activeHitboxes = 0;  // of which active
  std::uint32_t changes = 0;         // instance state changes in the last update
};

class SceneCulling {
 public:
  SceneCulling(const Scene& scene, const CullingOptions& options);

  // Before each frame's trace: the frame's camera and image aspect, and the counters of the
  // previous frame's trace (instanceCount() + hitboxCount() values; empty before the first
  // frame, and for the modes without feedback) with the rays it traced. `rayWeight` scales
  // the minimum activation counts: a frame's trace counts 1 in feedbackStride blocks of
  // pixels and N of P paths, each counted ray adding rayWeight = feedbackStride * P / N to its
  // counter, so the minimums ask for that many counted rays; a look's probe adds 1 a ray
  // (rayWeight 1), and a sparse look, one ray per step x step pixels, passes 1 / step^2, so
  // that one of its rays reaching an instance activates it.
  void update(const Camera& camera, float aspect, std::span<const std::uint32_t> hits,
              std::uint64_t rays, double rayWeight = 1.0);

  std::uint32_t instanceCount() const { return static_cast<std::uint32_t>(states_.size()); }
  std::uint32_t hitboxCount() const { return static_cast<std::uint32_t>(hitboxActive_.size()); }
  // Counter slots the trace writes: one per instance (its hits, or its box's when
  // omitted), then one per hitbox (its box's, when inactive).
  std::uint32_t counterCount() const { return instanceCount() + hitboxCount(); }

  const std::vector<InstanceState>& states() const { return states_; }
  const std::vector<Bounds>& bounds() const { return bounds_; }
  bool hitboxActive(std::uint32_t h) const { return hitboxActive_[h] != 0; }
  // A hitbox's box: its grid cell in x and z, the height range of its instances.
  const Bounds& hitboxBounds(std::uint32_t h) const { return hitboxBounds_[h]; }
  // Whether a hitbox holds instances (an empty cell has no box: nothing to activate).
  bool hitboxUsed(std::uint32_t h) const { return !hitboxInstances_[h].empty(); }
  std::uint32_t hitboxOf(std::uint32_t instance) const { return instanceHitbox_[instance]; }
  const CullingCounts& counts() const { return counts_; }

  // LiPaC's look, instead of activating every instance that appears large in the frustum:
  // the inactive hitboxes the frustum reaches become active, their instances with their own
  // BLAS omitted (a counting box each) and the shared ones active; active hitboxes keep their
  // states. The renderer traces the camera once with these states (the probe, its image
  // discarded), then update() with its counters activates the omitted instances its rays
  // reached above σ_a, as on any frame, and nothing in this frustum counts as appearing: the
  // frame holds what the camera reaches, not all it faces. wantsLook: before the first frame,
  // or when at least `lookAppearing` own-BLAS instances not active would appear large.
  bool wantsLook(const Camera& camera, float aspect) const;
  void look(const Camera& camera, float aspect);

 private:
  void updateFrustum(const Frustum& frustum, const Camera& camera);
  void updateLipac(const Frustum& frustum, const Camera& camera,
                   std::span<const std::uint32_t> hits, std::uint64_t rays, double rayWeight);
  void setState(std::uint32_t instance, InstanceState state);
  // A counting frame of a hitbox or an instance in the TLAS, `low` below its deactivation
  // threshold: whether it leaves now (then its wait doubles, up to the cap).
  bool countInFrame(DepartureWait& wait, bool low) const;
  // The cap of a wait, and the run of counting frames without a low one that halves it.
  std::uint32_t longestWait() const { return options_.lowFrames << kDepartureWaitMaxDoublings; }
  // A counting frame in which it is out, or in above its threshold: its wait halves back
  // towards lowFrames after longestWait() of these in a row.
  void countSettledFrame(DepartureWait& wait) const;
  // Its bounding sphere is at least appearMinFraction of the vertical field of view.
  bool appearsLarge(std::uint32_t instance, const Camera& camera) const;
  void count();

  CullingOptions options_;
  std::vector<Bounds> bounds_;
  std::vector<std::uint8_t> ownBlas_;  // the instance's mesh has no other instance
  // Never culled: lights' quads, and instances wider than two hitboxes (the ground), which
  // no one hitbox stands for.
  std::vector<std::uint8_t> alwaysOn_;
  std::vector<InstanceState> states_;
  std::vector<std::uint8_t> inFrustum_;  // last update's frustum test (lipac)
  std::vector<DepartureWait> instanceWaits_;
  // Activated on appearing in the frustum while its hitbox was inactive: it stays while it
  // is hit, until its hitbox activates (then the hitbox's rules hold).
  std::vector<std::uint8_t> appeared_;
  std::vector<std::uint32_t> instanceHitbox_;
  std::vector<std::vector<std::uint32_t>> hitboxInstances_;
  std::vector<Bounds> hitboxBounds_;
  std::vector<std::uint8_t> hitboxActive_;
  // A hitbox whose box sees many rays but whose instances see few waits longer each time it
  // leaves, so it settles instead of cycling.
  std::vector<DepartureWait> hitboxWaits_;
  CullingCounts counts_;
  bool first_ = true;
};

}  // namespace memograph::runtime
