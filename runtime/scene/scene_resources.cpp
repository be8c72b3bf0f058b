#include "runtime/scene/scene_resources.h"

#include "runtime/scene/scene_limits.h"

namespace memograph::runtime {

SceneResources uploadSceneResources(
    const VulkanContext& context, const Scene& scene,
    const std::vector<MaterialRef::EmissionKind>& emissionKinds,
    const std::vector<std::string>& texturePaths,
    const std::function<TextureImage(const std::string& path)>& loadTexture) {
  std::vector<TextureImage> textureImages;
  // The texels loaded so far, refused as soon as they pass the limit: the next texture is
  // not read once the host holds as much as the device is allowed.
  std::uint64_t texels = 0;
  for (const auto& path : texturePaths) {
    textureImages.push_back(loadTexture(path));
    if (!textureImages.back().levels.empty())
      texels += std::uint64_t(textureImages.back().levels.front().width) *
                textureImages.back().levels.front().height;
    checkTextureLimits(texturePaths.size(), texels);
  }
  return SceneResources{uploadScene(context, scene, emissionKinds),
                        std::make_unique<GpuTextures>(context, textureImages)};
}

}  // namespace memograph::runtime
