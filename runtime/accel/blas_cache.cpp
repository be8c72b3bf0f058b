#include "runtime/accel/blas_cache.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace memograph::runtime {

BlasCache::BlasCache(const VulkanContext& context, const GpuBuffer& vertices,
                     std::uint32_t vertexStride, const GpuBuffer& indices,
                     std::vector<MeshGeometry> meshes, std::uint64_t budgetBytes,
                     std::uint64_t buildTriangles, double buildMilliseconds,
                     std::uint32_t keepFrames)
    : context_(context),
      vertices_(vertices),
      vertexStride_(vertexStride),
      indices_(indices),
      meshes_(std::move(meshes)),
      budgetBytes_(budgetBytes),
      buildTriangles_(buildTriangles),
      buildMilliseconds_(buildMilliseconds),
      keepFrames_(keepFrames),
      blases_(meshes_.size()),
      lastUsed_(meshes_.size(), 0) {}

BlasFrameWork BlasCache::prepare(std::span<const std::uint32_t> needed, std::uint32_t frame) {
  BlasFrameWork work;
  std::vector<std::uint8_t> wanted(meshes_.size(), 0);
  for (std::uint32_t mesh : needed) {
    if (mesh >= meshes_.size())
      throw std::logic_error("BlasCache: mesh " + std::to_string(mesh) + " of " +
                             std::to_string(meshes_.size()));
    wanted[mesh] = 1;
  }

  // Builds, lowest mesh index first, each that fits in what is left of the triangle and
  // time budgets (at least one a frame, so a mesh larger than the budget still comes), in
  // one batch; except while the time budget has no measured build rate: then the first
  // mesh is built alone, and its timestamps size a second batch.
  std::vector<std::uint32_t> pending;
  for (std::uint32_t mesh = 0; mesh < meshes_.size(); ++mesh)
    if (wanted[mesh] && !blases_[mesh])
      pending.push_back(mesh);
  bool calibrating = buildMilliseconds_ > 0.0 && measuredTriangles_ == 0.0;
  while (!pending.empty()) {
    double left = buildTriangles_ ? double(buildTriangles_) - double(work.trianglesBuilt)
                                  : std::numeric_limits<double>::infinity();
    // The time left at the builds' measured rate (the renderer refuses the time budget on a
    // device without timestamps; a build too short to tick leaves the rate unmeasured).
    if (buildMilliseconds_ > 0.0 && measuredMilliseconds_ > 0.0)
      left = std::min(left, (buildMilliseconds_ - work.gpuMilliseconds) * measuredTriangles_ /
                                measuredMilliseconds_);
    std::vector<std::uint32_t> batch, later;
    std::vector<MeshGeometry> geometry;
    std::uint64_t batchTriangles = 0;
    for (const std::uint32_t mesh : pending) {
      const std::uint64_t triangles = meshes_[mesh].triangleCount;
      const bool first = work.builds == 0 && batch.empty();
      if (first || (!calibrating && double(batchTriangles + triangles) <= left)) {
        batch.push_back(mesh);
        geometry.push_back(meshes_[mesh]);
        batchTriangles += triangles;
      } else {
        later.push_back(mesh);
      }
    }
    pending = std::move(later);
    if (batch.empty())
      break;
    CompactedBlases built =
        buildCompactedBlases(context_, vertices_, vertexStride_, indices_, geometry);
    for (std::size_t k = 0; k < batch.size(); ++k) {
      blases_[batch[k]] = std::move(built.blases[k]);
      residentBytes_ += blases_[batch[k]]->size();
      ++residentCount_;
    }
    work.builds += static_cast<std::uint32_t>(batch.size());
    work.trianglesBuilt += batchTriangles;
    work.scratchBytes = std::max(work.scratchBytes, built.scratchBytes);
    work.gpuMilliseconds += built.gpuMilliseconds;
    measuredTriangles_ += double(batchTriangles);
    measuredMilliseconds_ += built.gpuMilliseconds;
    if (!calibrating)
      break;
    calibrating = false;
  }
  work.waiting = static_cast<std::uint32_t>(pending.size());
  for (std::uint32_t mesh = 0; mesh < meshes_.size(); ++mesh)
    if (wanted[mesh] && blases_[mesh])
      lastUsed_[mesh] = frame + 1;

  // BLASes no frame has used for more than keepFrames frames go.
  auto evict = [&](std::uint32_t mesh) {
    residentBytes_ -= blases_[mesh]->size();
    --residentCount_;
    blases_[mesh].reset();
    ++work.evictions;
  };
  if (keepFrames_)
    for (std::uint32_t mesh = 0; mesh < meshes_.size(); ++mesh)
      if (blases_[mesh] && frame + 1 - lastUsed_[mesh] > keepFrames_)
        evict(mesh);
  // Then those this frame does not use, least recently used first (ties: lowest mesh
  // index), while over the budget. What this frame uses stays even past the budget.
  if (budgetBytes_ && residentBytes_ > budgetBytes_) {
    std::vector<std::uint32_t> unused;
    for (std::uint32_t mesh = 0; mesh < meshes_.size(); ++mesh)
      if (blases_[mesh] && lastUsed_[mesh] != frame + 1)
        unused.push_back(mesh);
    std::stable_sort(unused.begin(), unused.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return lastUsed_[a] < lastUsed_[b]; });
    for (std::uint32_t mesh : unused) {
      if (residentBytes_ <= budgetBytes_)
        break;
      evict(mesh);
    }
  }
  return work;
}

VkDeviceAddress BlasCache::address(std::uint32_t mesh) const {
  return mesh < blases_.size() && blases_[mesh] ? blases_[mesh]->address() : 0;
}

}  // namespace memograph::runtime
