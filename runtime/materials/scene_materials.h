// The link stage of Renderer::render: the scene's material graphs compiled to GLSL, and what
// their emission tells next-event estimation (thesis §5.2), before the architecture is chosen.
#pragma once

#include <filesystem>
#include <vector>

#include "runtime/materials/material_linker.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

struct SceneMaterials {
  LinkedMaterials linked;
  // Per scene material, the emission NEE may take as known (emissionKindsVerified).
  std::vector<MaterialRef::EmissionKind> emissionKinds;
  // Some emitter's emission NEE must take from its graph: the megakernel's second material
  // call site (MG_NEE_EVALUATES_EMISSION), which the wavefront does not have.
  bool neeEvaluatesEmission = false;
  // Per distinct graph (LinkedMaterials::distinct), whether NEE evaluates it at an emitter's
  // light samples: only those graphs' wavefront material passes evaluate light points.
  std::vector<bool> neeEvaluatedGraphs;
};

// `nodeLibraryDirectory` empty: the embedded node library; `cacheKeyDomains` the key domains
// the cache takes (CacheOptions::keyDomains).
SceneMaterials linkSceneMaterials(const Scene& scene,
                                  const std::filesystem::path& nodeLibraryDirectory,
                                  std::uint32_t cacheKeyDomains = kCacheKeysAll);

}  // namespace memograph::runtime
