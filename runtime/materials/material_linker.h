// Links a scene's material graphs into the path tracer: compiles each graph with the
// compiler library (thesis §5.1) and generates the GLSL the two material dispatches need:
// for the switch, "materials.glsl" with every compiled include followed by
// evaluateMaterialSwitch(), a switch on the scene's material id that calls each
// EvaluateMaterial_<Name> with its first texture slot, and (under MG_CACHE_CUTS, for the
// texel cache's cut keys) the switches over EvaluateMaterialCut_<Name> and
// EvaluateMaterialRest_<Name> with the cut's values as a float array; for callable shaders, only
// the prelude (MaterialInputs, MaterialOutputs) for the raygen shader, and each material's own
// include for its callable.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "runtime/materials/material_instances.h"
#include "runtime/memo/cache_options.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

struct LinkedMaterial {
  std::string name;     // the EvaluateMaterial_<name> it calls
  int textureBase = 0;  // first slot of its textures in LinkedMaterials::texturePaths
  bool cacheable = false;
  // Texel cache (thesis §5.3.1): which outputs an entry stores (gpu::kCacheOutput* bits of
  // the graph's written outputs; 0 when not cacheable) and how many floats that is.
  std::uint32_t cacheOutputMask = 0;
  std::uint32_t cacheValueCount = 0;
  // The cut the texel cache keys instead (compiler/cut.h), for materials that are not
  // cacheable as a whole: gpu::kCacheCut* (kCacheCutNone for cacheable materials, which keep
  // their whole-output entries, and for materials without a cut), the cut's floats, and
  // whether an object-space key names the instance (the graph reads Object Info's
  // per-instance members) or only the mesh (every instance of a mesh shares entries).
  std::uint32_t cutDomain = 0;
  std::uint32_t cutWidth = 0;
  bool cutKeyedByInstance = false;
  // Keyed by its cut and reads no traced input: in the wavefront with unfiltered reads the
  // lookup and material passes hand the shade pass the cut's values, and the shade pass runs
  // the rest (docs/design/wavefront.md, "The caches in the wavefront"). A graph with
  // Ambient Occlusion or Bevel keeps its rest in its material pass, which has the traced
  // values.
  bool restInShade = false;
  // The cut's share of the graph's estimated cost (compiler metadata cutCostShare; 0 without
  // a cut): what a cached cut saves, for the cached-share statistic (RenderStats).
  double cutCostShare = 0.0;
  // The graph's estimated cost (compiler metadata estimatedCost): its weight in that
  // statistic.
  double estimatedCost = 0.0;
  // Index into LinkedMaterials::distinct: scene materials sharing a graph share one
  // compiled include (and one callable shader).
  std::uint32_t distinctIndex = 0;
  // The MaterialInputs members the graph reads and how many textures it samples (compiler
  // metadata): none of either means every output is a constant.
  std::vector<std::string> inputsUsed;
  std::size_t textureCount = 0;
  // The rays the path tracer traces for the graph's Ambient Occlusion node before it runs
  // (compiler metadata; docs/design/traced-inputs.md): as Cycles' settings. Samples 0: none.
  float ambientOcclusionDistance = 0.0f;
  std::uint32_t ambientOcclusionSamples = 0;
  std::uint32_t ambientOcclusionFlags = 0;  // kAmbientOcclusionInside | ...OnlyLocal bits
  // Likewise the Bevel node's rays (samples 0: none; the input is the shading normal).
  float bevelRadius = 0.0f;
  std::uint32_t bevelSamples = 0;
  // The graph calls TransparentBsdf (perhaps under a Mix or Add Shader) or writes an opacity
  // that may be below 1: a shadow ray that hits it evaluates the graph and passes through,
  // tinted by its transparency (transparent_shadow.glsl); a shadow ray stops at any other
  // material.
  bool transparentShadow = false;
  // The graph writes an opacity that may be below 1 (compiler metadata opacityBelowOne): a
  // path that hits it evaluates the graph in the trace and passes through with probability
  // 1 - opacity (stochastic_opacity.glsl); it is also a transparentShadow material.
  bool stochasticOpacity = false;
};

// LinkedMaterial::ambientOcclusionFlags, as ambient_occlusion.glsl's kAmbientOcclusion*.
constexpr std::uint32_t kAmbientOcclusionInside = 1;
constexpr std::uint32_t kAmbientOcclusionOnlyLocal = 2;

// One distinct compiled graph: what a callable shader of its own needs.
struct DistinctMaterial {
  std::string name;     // EvaluateMaterial_<name>
  std::string include;  // the compiler's GLSL include (prelude, node functions, function)
  int textureBase = 0;
  // Its cut's floats where the texel cache may key it by its cut (LinkedMaterial::cutWidth;
  // 0: none): its include then has MaterialCut_<name>, EvaluateMaterialCut_<name> and
  // EvaluateMaterialRest_<name>, which the wavefront's material pass calls.
  std::uint32_t cutWidth = 0;
  // Cacheable as a whole (LinkedMaterial::cacheable): the wavefront's material pass compiles
  // its insert only then (MG_MATERIAL_CACHEABLE).
  bool cacheable = false;
  // LinkedMaterial::restInShade: where the wavefront hands the shade pass the cut's values,
  // its material pass runs no rest but for light points (MG_MATERIAL_REST_IN_SHADE).
  bool restInShade = false;
};

// Distinct graphs of one shape, which share one wavefront material pass (material
// instances, material_instances.h).
struct MaterialInstanceGroup {
  std::string name;         // the EvaluateMaterial_<name> of `include`: the first member's graph
  std::string include;      // that graph's include, its differing constants read as parameters
  InstanceGroup instances;  // members: indices into LinkedMaterials::distinct
};

struct LinkedMaterials {
  std::string source;         // materials.glsl for the switch dispatch
  std::string preludeSource;  // materials.glsl for the callable dispatch
  // material_rests.glsl for the wavefront's shade pass: the graphs whose rest it runs
  // (LinkedMaterial::restInShade) and evaluateMaterialRestInShade, which runs a material's
  // rest from its cut's values. Guarded by MG_CACHE_CUTS.
  std::string shadeRestSource;
  std::vector<LinkedMaterial> materials;  // parallel to Scene::materials
  std::vector<DistinctMaterial> distinct;
  // The distinct graphs by shape: each in exactly one group, the groups in the order of their
  // first members.
  std::vector<MaterialInstanceGroup> instanceGroups;
  std::vector<std::string> texturePaths;  // resolved paths, in descriptor-array order
  // Floats per texel-cache entry: the largest cacheValueCount (0: nothing is cacheable).
  std::uint32_t cacheValueCount = 0;
  // The largest cutWidth (0: no material is keyed by its cut). The switch dispatch's and the
  // wavefront's texel cache key cuts (MG_CACHE_CUTS): its entries then hold the larger of
  // the two.
  std::uint32_t cutValueCount = 0;
  // Some material writes specularTint or cyclesPrincipled: the path tracer needs
  // MG_CYCLES_PRINCIPLED (brdf.glsl), which other scenes do without.
  bool cyclesPrincipled = false;
  // Some material writes BSDF lobes (nodes/bsdf.inc): the path tracer needs MG_BSDF_LOBES
  // (bsdf_lobes.glsl), which other scenes do without, so their kernels stay as they were.
  bool bsdfLobes = false;
  // Some graph calls PrincipledLayers or PrincipledBsdf (Principled v1's sheen, clearcoat and
  // transmission as lobes, or a Principled BSDF among other shaders): the path tracer needs
  // MG_PRINCIPLED_LAYERS (bsdf_lobes.glsl), which scenes of other lobes do without.
  bool principledLayers = false;
  // Some graph calls ChooseShader (a Mix or Add Shader chosen per hit): mg_addLobe needs
  // MG_CLOSURE_CHOICE, which other scenes do without, so their kernels stay as they were.
  bool closureChoice = false;
  // Some graph gives a lobe its own normal (a BSDF sink's Normal, PrincipledLayers'
  // ClearcoatNormal; the compiler's `lobeNormals` output): the path tracer needs
  // MG_LOBE_NORMALS (bsdf_lobes.glsl's per-lobe frames), which other scenes of lobes do without.
  bool lobeNormals = false;
  // Some material may be transparent (LinkedMaterial::transparentShadow): the path tracer
  // needs MG_TRANSPARENT_SHADOWS (transparent_shadow.glsl), and materials.glsl then holds
  // materialTransparentShadow and, with the switch, evaluateMaterialAtShadowHit; scenes
  // without one trace opaque shadow rays, as they always did.
  bool transparentShadows = false;
  // Some material writes an opacity that may be below 1 (LinkedMaterial::stochasticOpacity):
  // the path tracer needs MG_STOCHASTIC_OPACITY (stochastic_opacity.glsl), and materials.glsl
  // then holds materialStochasticOpacity; it implies transparentShadows, whose switch
  // (evaluateMaterialAtShadowHit) the path's trace calls. Scenes without one trace as before.
  bool stochasticOpacity = false;
  // shadow_materials.glsl for the wavefront's shadow pass: the maybe-transparent graphs'
  // includes and evaluateMaterialAtShadowHit over them (empty without such a material).
  std::string shadowSource;
  // Some material reads an object-space input (generated, objectPosition, geometricNormal,
  // objectLocation, objectRandom, backfacing); without one the shaders define
  // MG_OMIT_OBJECT_INPUTS and MaterialInputs carries none of them.
  bool objectInputs = false;
  // Some material reads the path state (Light Path: rayFlags, rayLength, the depths); without
  // one the shaders define MG_OMIT_PATH_INPUTS, MaterialInputs carries none of it and the
  // path tracer tracks no path state.
  bool pathInputs = false;
  // Some material reads a traced input (Ambient Occlusion, Bevel): the megakernel traces its
  // rays from each hit before the graph runs and materials.glsl holds
  // mg_materialAmbientOcclusion and mg_materialBevel, each scene material's settings; without
  // one the shaders define MG_OMIT_TRACED_INPUTS.
  bool tracedInputs = false;
  double compileMilliseconds = 0.0;
};

// How the path tracer reaches a scene material's graph: a switch in the one path-tracer
// shader (both backends), or a callable shader per material (ray-tracing pipeline only).
// Auto: callable on the pipeline backend, switch on the query backend.
enum class MaterialDispatch { Auto, Switch, Callable };

const char* materialDispatchName(MaterialDispatch dispatch);
// Parses "auto", "switch" or "callable"; throws std::invalid_argument naming the choices.
MaterialDispatch parseMaterialDispatch(const std::string& text);

// The PCG hash of the shaders' mg_pcg (O'Neill 2014; Jarzynski and Olano 2020), on the host.
std::uint32_t pcgHash(std::uint32_t v);

// The compiler's cutDomain ("none", "uv", "object", "world") → gpu::kCacheCut*. Throws
// std::runtime_error on a name it does not know.
std::uint32_t cacheCutDomain(const std::string& cutDomain);

// Members of MaterialOutputs named by the compiler's outputsWritten → gpu::kCacheOutput* bits
// and their float count. Throws std::runtime_error on a name it does not know.
std::uint32_t cacheOutputMask(const std::vector<std::string>& outputsWritten,
                              std::uint32_t* valueCount = nullptr);

struct MaterialLinkOptions {
  // A node-library folder that replaces the embedded one (for --nodes DIR); empty: embedded.
  std::filesystem::path nodeLibraryDirectory;
  // The key domains the cache takes (kCacheKey* of cache_options.h): a material keyed in
  // another is linked as uncacheable, with no cut, so it never touches the cache.
  std::uint32_t cacheKeyDomains = kCacheKeysAll;
};

// Throws std::runtime_error with the compiler's diagnostics (file:line:col) when a graph is
// missing or does not compile.
LinkedMaterials linkMaterials(const std::vector<MaterialRef>& materials,
                              const MaterialLinkOptions& options = {});

}  // namespace memograph::runtime
