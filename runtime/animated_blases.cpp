#include "runtime/animated_blases.h"

#include <algorithm>
#include <stdexcept>

namespace memograph::runtime {

namespace {

constexpr VkBuildAccelerationStructureFlagsKHR kAnimatedFlags =
    VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR |
    VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;

// The upload's record of a vertex (scene_upload.cpp): position and normal with u and v in w.
gpu::Vertex vertexRecord(const Mesh& mesh, std::size_t v, glm::vec3 position, glm::vec3 normal) {
  const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
  gpu::Vertex out;
  out.position = glm::vec4(position, uv.x);
  out.normal = glm::vec4(normal, uv.y);
  out.tangent = mesh.tangents.empty() ? glm::vec4(0.0f) : mesh.tangents[v];
  out.color = mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[v];
  return out;
}

// Area-weighted normals of the triangles around each vertex; `sign` turns them to the side
// the mesh's own normals face (its winding may be either).
void triangleNormals(const Mesh& mesh, const std::vector<glm::vec3>& positions, float sign,
                     std::vector<glm::vec3>& normals) {
  normals.assign(positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const float length = glm::length(normals[v]);
    normals[v] = length > 1e-20f ? sign * normals[v] / length : mesh.normals[v];
  }
}

}  // namespace

AnimatedBlases::AnimatedBlases(const VulkanContext& context, const Scene& scene,
                               SceneBuffers& buffers, std::uint32_t rebuildEvery)
    : context_(context),
      scene_(scene),
      buffers_(buffers),
      rebuildEvery_(std::max(rebuildEvery, 1u)),
      slotOfMesh_(scene.meshes.size(), -1) {
  const DeviceFunctions& f = context.functions();
  const VkDeviceSize scratchAlignment =
      context.info().minAccelerationStructureScratchOffsetAlignment;
  VkDeviceSize scratchTotal = 0, stagingBytes = 0;
  for (std::size_t k = 0; k < scene.animatedMeshes.size(); ++k) {
    const std::uint32_t mesh = scene.animatedMeshes[k];
    Animated a;
    a.mesh = mesh;
    a.k = k;
    a.geometry = buffers.geometry.at(mesh);
    // Which side the winding's normals face against the mesh's own, at rest.
    std::vector<glm::vec3> restNormals;
    const Mesh& sceneMesh = scene.meshes[mesh];
    triangleNormals(sceneMesh, sceneMesh.positions, 1.0f, restNormals);
    float agreement = 0.0f;
    for (std::size_t v = 0; v < restNormals.size(); ++v)
      agreement += glm::dot(restNormals[v], sceneMesh.normals[v]);
    a.normalSign = agreement < 0.0f ? -1.0f : 1.0f;
    VkAccelerationStructureGeometryKHR geometry =
        meshGeometry(buffers.vertices, sizeof(gpu::Vertex), buffers.indices, a.geometry);
    VkAccelerationStructureBuildGeometryInfoKHR build =
        buildGeometryInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, kAnimatedFlags,
                          VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR, &geometry);
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    f.getAccelerationStructureBuildSizes(context.device(),
                                         VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build,
                                         &a.geometry.triangleCount, &sizes);
    a.blas = AccelerationStructure(context, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                                   sizes.accelerationStructureSize);
    bytes_ += sizes.accelerationStructureSize;
    // One slice each, large enough for a rebuild or an update, so a frame's builds batch.
    a.scratchOffset = scratchTotal;
    scratchTotal = alignUp(scratchTotal + std::max(sizes.buildScratchSize, sizes.updateScratchSize),
                           scratchAlignment);
    stagingBytes += VkDeviceSize(a.geometry.vertexCount) * sizeof(gpu::Vertex);
    slotOfMesh_[mesh] = static_cast<std::int32_t>(meshes_.size());
    meshes_.push_back(std::move(a));
  }
  if (meshes_.empty())
    return;
  scratch_ =
      GpuBuffer(context, scratchTotal + scratchAlignment,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  staging_ = hostBuffer(context, stagingBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  // The first build, at rest (the uploaded vertices): every BLAS, one batch.
  for (std::size_t slot = 0; slot < meshes_.size(); ++slot) {
    planned_.push_back(slot);
    plannedUpdate_.push_back(0);
  }
  context.submitAndWait([&](VkCommandBuffer commands) { record(commands); });
  for (Animated& a : meshes_)
    a.current = true;
  planned_.clear();
  plannedUpdate_.clear();
}

VkDeviceAddress AnimatedBlases::address(std::uint32_t mesh) const {
  if (mesh >= slotOfMesh_.size() || slotOfMesh_[mesh] < 0)
    return 0;
  return meshes_[std::size_t(slotOfMesh_[mesh])].blas.address();
}

AnimatedFrameWork AnimatedBlases::prepare(float seconds, std::uint32_t frame,
                                          const std::vector<std::uint8_t>& needed) {
  AnimatedFrameWork work;
  copies_.clear();
  planned_.clear();
  plannedUpdate_.clear();
  if (!scene_.animatedPosition)
    return work;  // drawn at rest
  auto* staging = static_cast<gpu::Vertex*>(staging_.mapped());
  VkDeviceSize stagingOffset = 0;
  std::vector<glm::vec3> positions, normals;
  for (std::size_t slot = 0; slot < meshes_.size(); ++slot) {
    Animated& a = meshes_[slot];
    if (!needed.empty() && !needed[a.mesh]) {
      a.current = false;  // left behind: rebuilt when it is needed again
      continue;
    }
    const Mesh& mesh = scene_.meshes[a.mesh];
    positions.resize(mesh.positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v)
      positions[v] = scene_.animatedPosition(a.k, mesh.positions[v], seconds);
    triangleNormals(mesh, positions, a.normalSign, normals);
    gpu::Vertex* out = staging + stagingOffset / sizeof(gpu::Vertex);
    for (std::size_t v = 0; v < positions.size(); ++v)
      out[v] = vertexRecord(mesh, v, positions[v], normals[v]);
    const VkDeviceSize bytes = VkDeviceSize(positions.size()) * sizeof(gpu::Vertex);
    copies_.push_back(
        {stagingOffset, VkDeviceSize(a.geometry.firstVertex) * sizeof(gpu::Vertex), bytes});
    stagingOffset += bytes;
    // builtAfter: the frame after the last build (0: the first build, before frame 0).
    const bool rebuild = !a.current || frame + 1 - a.builtAfter >= rebuildEvery_;
    if (rebuild)
      a.builtAfter = frame + 1;
    a.current = true;
    planned_.push_back(slot);
    plannedUpdate_.push_back(rebuild ? 0 : 1);
    ++(rebuild ? work.rebuilds : work.updates);
  }
  return work;
}

void AnimatedBlases::record(VkCommandBuffer commands) const {
  if (planned_.empty())
    return;
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  if (!copies_.empty()) {
    vkCmdCopyBuffer(commands, staging_.buffer(), buffers_.vertices.buffer(),
                    static_cast<std::uint32_t>(copies_.size()), copies_.data());
    // The moved vertices, before the BLAS builds read them and the trace shades them.
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
  }
  const VkDeviceSize scratchAlignment =
      context_.info().minAccelerationStructureScratchOffsetAlignment;
  const VkDeviceAddress scratchBase = alignUp(scratch_.address(), scratchAlignment);
  std::vector<VkAccelerationStructureGeometryKHR> geometries(planned_.size());
  std::vector<VkAccelerationStructureBuildGeometryInfoKHR> builds(planned_.size());
  std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges(planned_.size());
  std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePointers(planned_.size());
  for (std::size_t i = 0; i < planned_.size(); ++i) {
    const Animated& a = meshes_[planned_[i]];
    geometries[i] =
        meshGeometry(buffers_.vertices, sizeof(gpu::Vertex), buffers_.indices, a.geometry);
    VkAccelerationStructureBuildGeometryInfoKHR& b = builds[i];
    b = buildGeometryInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, kAnimatedFlags,
                          plannedUpdate_[i] ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR
                                            : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
                          &geometries[i]);
    b.srcAccelerationStructure = plannedUpdate_[i] ? a.blas.handle() : VK_NULL_HANDLE;
    b.dstAccelerationStructure = a.blas.handle();
    b.scratchData.deviceAddress = scratchBase + a.scratchOffset;
    ranges[i] = {a.geometry.triangleCount, 0, 0, 0};
    rangePointers[i] = &ranges[i];
  }
  context_.functions().cmdBuildAccelerationStructures(
      commands, static_cast<std::uint32_t>(builds.size()), builds.data(), rangePointers.data());
  // The BLASes, before the TLAS build and the trace read them.
  barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
  barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace memograph::runtime
