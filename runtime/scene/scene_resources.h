// The upload stage of Renderer::render: the scene's geometry, lights and environment
// (uploadScene) and the textures its materials name, on the device.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/scene/gpu_textures.h"
#include "runtime/scene/scene.h"
#include "runtime/scene/scene_upload.h"
#include "runtime/vk/vulkan_context.h"

namespace memograph::runtime {

struct SceneResources {
  SceneBuffers buffers;
  std::unique_ptr<GpuTextures> textures;
};

// `texturePaths` in descriptor-array order (LinkedMaterials::texturePaths), each read with
// `loadTexture` (which throws naming the path) before anything is uploaded.
SceneResources uploadSceneResources(
    const VulkanContext& context, const Scene& scene,
    const std::vector<MaterialRef::EmissionKind>& emissionKinds,
    const std::vector<std::string>& texturePaths,
    const std::function<TextureImage(const std::string& path)>& loadTexture);

}  // namespace memograph::runtime
