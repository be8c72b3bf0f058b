#include "runtime/materials/scene_materials.h"

#include "runtime/scene/scene_upload.h"

namespace memograph::runtime {

SceneMaterials linkSceneMaterials(const Scene& scene,
                                  const std::filesystem::path& nodeLibraryDirectory,
                                  std::uint32_t cacheKeyDomains) {
  MaterialLinkOptions linkOptions;
  linkOptions.nodeLibraryDirectory = nodeLibraryDirectory;
  linkOptions.cacheKeyDomains = cacheKeyDomains;
  SceneMaterials materials;
  materials.linked = linkMaterials(scene.materials, linkOptions);
  materials.emissionKinds = emissionKindsVerified(scene, materials.linked);
  materials.neeEvaluatesEmission = sceneNeeEvaluatesEmission(scene, materials.emissionKinds);
  return materials;
}

}  // namespace memograph::runtime
