#include "runtime/accel/animated_blases.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "runtime/vk/compute_pipeline.h"

namespace memograph::runtime {

namespace {

constexpr VkBufferUsageFlags kShaderRead =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

constexpr VkBuildAccelerationStructureFlagsKHR kAnimatedFlags =
    VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR |
    VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;

// Whether the area-weighted normals of the mesh's triangles at rest face the side its own
// normals face (+1) or the other (-1, a winding the other way round): the vertex pass turns
// the moved triangles' normals by it.
float restNormalSign(const Mesh& mesh) {
  std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::vec3 n =
        glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    normals[a] += n;
    normals[b] += n;
    normals[c] += n;
  }
  float agreement = 0.0f;
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const float length = glm::length(normals[v]);
    if (length > 1e-20f)
      agreement += glm::dot(normals[v] / length, mesh.normals[v]);
  }
  return agreement < 0.0f ? -1.0f : 1.0f;
}

// Appends the mesh's rest vertices to `rest` and the triangles around each (their corners
// as indices into `rest`, in the mesh's index order) to `corners`.
void appendRestVertices(const Mesh& mesh, std::vector<gpu::VertexMotionRest>& rest,
                        std::vector<glm::uvec4>& corners) {
  const auto first = static_cast<std::uint32_t>(rest.size());
  std::vector<std::uint32_t> around(mesh.positions.size(), 0);
  for (const std::uint32_t index : mesh.indices)
    ++around[index];
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    gpu::VertexMotionRest r{};
    r.position = glm::vec4(mesh.positions[v], 0.0f);
    r.normal = glm::vec4(mesh.normals[v], 0.0f);
    r.triangles.y = around[v];
    rest.push_back(r);
  }
  // Each vertex's slice of the corner list, then its triangles in index order.
  auto firstCorner = static_cast<std::uint32_t>(corners.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    rest[first + v].triangles.x = firstCorner;
    firstCorner += around[v];
  }
  corners.resize(firstCorner);
  std::vector<std::uint32_t> filled(mesh.positions.size(), 0);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::uvec4 triangle(first + mesh.indices[t], first + mesh.indices[t + 1],
                              first + mesh.indices[t + 2], 0u);
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.indices[t + c];
      corners[rest[first + v].triangles.x + filled[v]++] = triangle;
    }
  }
}

}  // namespace

AnimatedBlases::AnimatedBlases(const VulkanContext& context, const Scene& scene,
                               SceneBuffers& buffers, std::uint32_t rebuildEvery,
                               const std::filesystem::path& shaderCacheDirectory)
    : context_(context),
      scene_(scene),
      buffers_(buffers),
      rebuildEvery_(std::max(rebuildEvery, 1u)),
      slotOfMesh_(scene.meshes.size(), -1) {
  const DeviceFunctions& f = context.functions();
  const VkDeviceSize scratchAlignment =
      context.info().minAccelerationStructureScratchOffsetAlignment;
  VkDeviceSize scratchTotal = 0;
  std::vector<gpu::VertexMotionRest> rest;
  std::vector<glm::uvec4> corners;
  // Without motions the meshes are drawn at rest: no vertex pass, nothing of it to make.
  const bool moves = !scene.animatedMotions.empty();
  for (std::size_t k = 0; k < scene.animatedMeshes.size(); ++k) {
    const std::uint32_t mesh = scene.animatedMeshes[k];
    Animated a;
    a.mesh = mesh;
    a.k = k;
    a.geometry = buffers.geometry.at(mesh);
    if (moves) {
      a.normalSign = restNormalSign(scene.meshes[mesh]);
      a.firstRest = static_cast<std::uint32_t>(rest.size());
      appendRestVertices(scene.meshes[mesh], rest, corners);
    }
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
    slotOfMesh_[mesh] = static_cast<std::int32_t>(meshes_.size());
    meshes_.push_back(std::move(a));
  }
  if (meshes_.empty())
    return;
  scratch_ =
      GpuBuffer(context, scratchTotal + scratchAlignment,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (moves) {
    rest_ = uploadBuffer<gpu::VertexMotionRest>(context, rest, kShaderRead);
    corners_ = uploadBuffer<glm::uvec4>(context, corners, kShaderRead);
    jobs_ = hostBuffer(context, meshes_.size() * sizeof(gpu::VertexMotionJob), kShaderRead);
    pass_ = createPushConstantPass(context, "vertex_motion.comp", sizeof(gpu::VertexMotionPush),
                                   shaderCacheDirectory, "vertex motion");
  }
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
  planned_.clear();
  plannedUpdate_.clear();
  movedMeshes_ = 0;
  movedMaxVertices_ = 0;
  seconds_ = seconds;
  if (scene_.animatedMotions.empty())
    return work;  // drawn at rest
  auto* jobs = static_cast<gpu::VertexMotionJob*>(jobs_.mapped());
  for (std::size_t slot = 0; slot < meshes_.size(); ++slot) {
    Animated& a = meshes_[slot];
    if (!needed.empty() && !needed[a.mesh]) {
      a.current = false;  // left behind: rebuilt when it is needed again
      continue;
    }
    gpu::VertexMotionJob& job = jobs[movedMeshes_++];
    job.motion = scene_.animatedMotions[a.k];
    job.range = glm::uvec4(a.geometry.firstVertex, a.geometry.vertexCount, a.firstRest,
                           std::bit_cast<std::uint32_t>(a.normalSign));
    movedMaxVertices_ = std::max(movedMaxVertices_, a.geometry.vertexCount);
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
  if (movedMeshes_ > 0) {
    gpu::VertexMotionPush push{};
    push.sources = glm::uvec4(addressWords(jobs_.address()), addressWords(rest_.address()));
    push.targets =
        glm::uvec4(addressWords(corners_.address()), addressWords(buffers_.vertices.address()));
    push.time = glm::vec4(seconds_, 0.0f, 0.0f, 0.0f);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pass_.pipeline.get());
    vkCmdPushConstants(commands, pass_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                       &push);
    vkCmdDispatch(
        commands,
        (movedMaxVertices_ + gpu::kVertexMotionWorkgroup - 1) / gpu::kVertexMotionWorkgroup,
        movedMeshes_, 1);
    // The moved vertices, before the BLAS builds read them (as shader reads in their own
    // stage) and the trace shades them.
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
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
