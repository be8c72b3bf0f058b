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
  materials.neeEvaluatedGraphs.assign(materials.linked.distinct.size(), false);
  const std::vector<bool> evaluated = neeEvaluatedMaterials(scene, materials.emissionKinds);
  for (std::size_t i = 0; i < evaluated.size() && i < materials.linked.materials.size(); ++i)
    if (evaluated[i])
      materials.neeEvaluatedGraphs[materials.linked.materials[i].distinctIndex] = true;
  return materials;
}

}  // namespace memograph::runtime
