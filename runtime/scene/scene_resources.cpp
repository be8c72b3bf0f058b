#include "runtime/scene/scene_resources.h"

namespace memograph::runtime {

SceneResources uploadSceneResources(
    const VulkanContext& context, const Scene& scene,
    const std::vector<MaterialRef::EmissionKind>& emissionKinds,
    const std::vector<std::string>& texturePaths,
    const std::function<TextureImage(const std::string& path)>& loadTexture) {
  std::vector<TextureImage> textureImages;
  for (const auto& path : texturePaths)
    textureImages.push_back(loadTexture(path));
  return SceneResources{uploadScene(context, scene, emissionKinds),
                        std::make_unique<GpuTextures>(context, textureImages)};
}

}  // namespace memograph::runtime
