#include "runtime/materials/material_linker.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "runtime/shaders/shared_types.h"

// Until the compiler lands on main, the runtime builds without it and says so at run time.
#if __has_include("compiler/compiler.h")
#define MG_HAVE_COMPILER 1
#include "compiler/compiler.h"
#include "compiler/diagnostics.h"
#include "compiler/material_interface.h"
#include "compiler/node_library.h"
#include "memograph/node_library_loader.h"
#endif

namespace memograph::runtime {

const char* materialDispatchName(MaterialDispatch dispatch) {
  switch (dispatch) {
    case MaterialDispatch::Auto:
      return "auto";
    case MaterialDispatch::Switch:
      return "switch";
    case MaterialDispatch::Callable:
      return "callable";
  }
  return "auto";
}

MaterialDispatch parseMaterialDispatch(const std::string& text) {
  if (text == "auto")
    return MaterialDispatch::Auto;
  if (text == "switch")
    return MaterialDispatch::Switch;
  if (text == "callable")
    return MaterialDispatch::Callable;
  throw std::invalid_argument("unknown material dispatch '" + text +
                              "' (choose auto, switch or callable)");
}

std::uint32_t pcgHash(std::uint32_t v) {
  std::uint32_t state = v * 747796405u + 2891336453u;
  std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

std::uint32_t cacheCutDomain(const std::string& cutDomain) {
  if (cutDomain == "none")
    return gpu::kCacheCutNone;
  if (cutDomain == "uv")
    return gpu::kCacheCutUv;
  if (cutDomain == "object")
    return gpu::kCacheCutObject;
  if (cutDomain == "world")
    return gpu::kCacheCutWorld;
  throw std::runtime_error("material cut domain '" + cutDomain + "' is unknown to the texel cache");
}

// The CacheOptions::keyDomains bit of a cut's domain (kCacheCut*).
std::uint32_t cacheKeyDomainOf(std::uint32_t cutDomain) {
  if (cutDomain == gpu::kCacheCutObject)
    return kCacheKeyObject;
  if (cutDomain == gpu::kCacheCutWorld)
    return kCacheKeyWorld;
  return kCacheKeyUv;
}

std::uint32_t cacheOutputMask(const std::vector<std::string>& outputsWritten,
                              std::uint32_t* valueCount) {
  struct Output {
    const char* name;
    std::uint32_t bit;
    std::uint32_t floats;
  };
  static const Output kOutputs[] = {
      {"baseColor", gpu::kCacheOutputBaseColor, 3},
      {"metallic", gpu::kCacheOutputMetallic, 1},
      {"roughness", gpu::kCacheOutputRoughness, 1},
      {"normal", gpu::kCacheOutputNormal, 3},
      {"emission", gpu::kCacheOutputEmission, 3},
      {"opacity", gpu::kCacheOutputOpacity, 1},
      {"specular", gpu::kCacheOutputSpecular, 1},
      {"specularTint", gpu::kCacheOutputSpecularTint, 1},
      {"cyclesPrincipled", gpu::kCacheOutputCyclesPrincipled, 1},
      {"lobes", gpu::kCacheOutputLobes, gpu::kCacheLobeValues},
      {"lobeNormals", gpu::kCacheOutputLobeNormals, gpu::kCacheLobeNormalValues}};
  std::uint32_t mask = 0, floats = 0;
  for (const std::string& name : outputsWritten) {
    bool known = false;
    for (const Output& output : kOutputs) {
      if (name == output.name) {
        if (!(mask & output.bit))
          floats += output.floats;
        mask |= output.bit;
        known = true;
      }
    }
    if (!known)
      throw std::runtime_error("material output '" + name + "' is unknown to the texel cache");
  }
  if (valueCount)
    *valueCount = floats;
  return mask;
}

#ifndef MG_HAVE_COMPILER
LinkedMaterials linkMaterials(const std::vector<MaterialRef>&, const MaterialLinkOptions&) {
  throw std::runtime_error(
      "this build has no material compiler (compiler/compiler.h was missing at build time)");
}
#else

namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return {};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The traced inputs' settings (ambient_occlusion.glsl setTracedInputs): per scene material
// x its AO distance as float bits, y its samples (0: no AO rays, the input is 1), z its
// kAmbientOcclusion* flags; and its Bevel radius (float bits) and samples. Only in scenes
// with a traced input, whose shaders read them.
std::string tracedInputTables(const std::vector<LinkedMaterial>& materials) {
  std::string table =
      "// Ambient Occlusion rays: x distance (float bits), y samples (0: none), z flags.\n";
  table += "const uvec4 mg_materialAmbientOcclusion[" + std::to_string(materials.size()) +
           "] = uvec4[](\n";
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const LinkedMaterial& m = materials[i];
    table += "    uvec4(" +
             std::to_string(std::bit_cast<std::uint32_t>(m.ambientOcclusionDistance)) + "u, " +
             std::to_string(m.ambientOcclusionSamples) + "u, " +
             std::to_string(m.ambientOcclusionFlags) + "u, 0u)" +
             (i + 1 < materials.size() ? ",\n" : ");\n");
  }
  table += "// Bevel rays: x radius (float bits), y samples (0: none).\n";
  table += "const uvec2 mg_materialBevel[" + std::to_string(materials.size()) + "] = uvec2[](\n";
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const LinkedMaterial& m = materials[i];
    table += "    uvec2(" + std::to_string(std::bit_cast<std::uint32_t>(m.bevelRadius)) + "u, " +
             std::to_string(m.bevelSamples) + "u)" + (i + 1 < materials.size() ? ",\n" : ");\n");
  }
  return table;
}

// The texel cache's cut keys (texel_cache.glsl, MG_CACHE_CUTS): per scene material its
// cut's domain, width and whether an object-space key names the instance. Both dispatches'
// materials.glsl carry it: the megakernel's switch and the wavefront's lookup and material
// passes (which see the prelude) key cuts alike (cacheCutKeyFor). Guarded: only a render
// that keys cuts defines MG_CACHE_CUTS.
std::string cutInfoTable(const std::vector<LinkedMaterial>& materials) {
  std::string out = "#ifdef MG_CACHE_CUTS\n";
  out +=
      "// Cut keys: x gpu::kCacheCut* domain, y width (floats), z 1: keyed by instance,\n"
      "// w 1: the wavefront's shade pass runs the rest (LinkedMaterial::restInShade).\n";
  out += "const uvec4 mg_materialCutInfo[" + std::to_string(materials.size()) + "] = uvec4[](\n";
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const LinkedMaterial& m = materials[i];
    out += "    uvec4(" + std::to_string(m.cutDomain) + "u, " + std::to_string(m.cutWidth) + "u, " +
           (m.cutKeyedByInstance ? "1u" : "0u") + ", " + (m.restInShade ? "1u" : "0u") + ")" +
           (i + 1 < materials.size() ? ",\n" : ");\n");
  }
  return out + "#endif  // MG_CACHE_CUTS\n";
}

// The includes of the distinct graphs of the scene materials that `wanted` picks, each once.
template <typename Predicate>
std::string includesOf(const LinkedMaterials& linked, Predicate wanted) {
  std::string out;
  std::vector<char> included(linked.distinct.size(), 0);
  for (const LinkedMaterial& m : linked.materials) {
    if (wanted(m) && !included[m.distinctIndex]) {
      included[m.distinctIndex] = 1;
      out += linked.distinct[m.distinctIndex].include;
    }
  }
  return out;
}

// The wavefront shade pass's rests (LinkedMaterials::shadeRestSource): the includes of the
// graphs whose rest the shade pass runs (LinkedMaterial::restInShade) and a switch over the
// scene materials that runs a material's rest from its cut's values.
std::string shadeRests(const LinkedMaterials& linked) {
  std::string out = "// Generated by memograph's material linker. Do not edit.\n";
  out += "#ifdef MG_CACHE_CUTS\n";
  out += includesOf(linked, [](const LinkedMaterial& m) { return m.restInShade; });
  out +=
      "// The outputs of scene material `materialId` at `inputs` from its cut's `values`.\n"
      "void evaluateMaterialRestInShade(uint materialId, MaterialInputs inputs, "
      "float values[MG_CACHE_VALUES], out MaterialOutputs outputs) {\n"
      "  switch (materialId) {\n";
  for (std::size_t i = 0; i < linked.materials.size(); ++i) {
    const LinkedMaterial& m = linked.materials[i];
    if (!m.restInShade)
      continue;
    out += "    case " + std::to_string(i) +
           "u: {\n      inputs.textureBase = " + std::to_string(m.textureBase) +
           ";\n      MaterialCut_" + m.name + " cut;\n";
    for (std::uint32_t k = 0; k < m.cutWidth; ++k)
      out += "      cut.v[" + std::to_string(k) + "] = values[" + std::to_string(k) + "];\n";
    out +=
        "      EvaluateMaterialRest_" + m.name + "(inputs, cut, outputs);\n      break;\n    }\n";
  }
  out += "    default:\n      outputs = mg_defaultMaterialOutputs(inputs);\n      break;\n  }\n}\n";
  return out + "#endif  // MG_CACHE_CUTS\n";
}

// The switch dispatch's two switches that evaluate a material's cut into the cache's float
// array (MG_CACHE_VALUES, at least every cut's width) and its rest from that array. Guarded:
// MG_CACHE_VALUES exists only with a cache. (The wavefront's material passes call their one
// graph's cut and rest directly: MG_EVALUATE_MATERIAL_CUT, material_shaders.cpp.)
std::string cutSwitches(const std::vector<LinkedMaterial>& materials) {
  std::string out = "#ifdef MG_CACHE_CUTS\n";
  std::string cut =
      "// The cut's values of scene material `materialId` at `inputs` (a key's centre).\n"
      "void evaluateMaterialCutSwitch(uint materialId, MaterialInputs inputs, "
      "out float values[MG_CACHE_VALUES]) {\n"
      "  for (uint i = 0u; i < uint(MG_CACHE_VALUES); ++i) values[i] = 0.0;\n"
      "  switch (materialId) {\n";
  std::string rest =
      "// The outputs of scene material `materialId` at `inputs` from its cut's `values`.\n"
      "void evaluateMaterialRestSwitch(uint materialId, MaterialInputs inputs, "
      "float values[MG_CACHE_VALUES], out MaterialOutputs outputs) {\n"
      "  switch (materialId) {\n";
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const LinkedMaterial& m = materials[i];
    if (m.cutDomain == gpu::kCacheCutNone)
      continue;
    const std::string type = "MaterialCut_" + m.name;
    const std::string head = "    case " + std::to_string(i) +
                             "u: {\n      inputs.textureBase = " + std::to_string(m.textureBase) +
                             ";\n      " + type + " cut;\n";
    cut += head + "      EvaluateMaterialCut_" + m.name + "(inputs, cut);\n";
    rest += head;
    for (std::uint32_t k = 0; k < m.cutWidth; ++k) {
      const std::string index = std::to_string(k);
      cut += "      values[" + index + "] = cut.v[" + index + "];\n";
      rest += "      cut.v[" + index + "] = values[" + index + "];\n";
    }
    rest += "      EvaluateMaterialRest_" + m.name + "(inputs, cut, outputs);\n";
    cut += "      break;\n    }\n";
    rest += "      break;\n    }\n";
  }
  cut += "    default:\n      break;\n  }\n}\n";
  rest +=
      "    default:\n      outputs = mg_defaultMaterialOutputs(inputs);\n      break;\n  }\n}\n";
  return out + cut + rest + "#endif  // MG_CACHE_CUTS\n";
}

// Transparent shadows (transparent_shadow.glsl), for scenes with a maybe-transparent material:
// materialTransparentShadow, which says of a scene material whether a shadow ray evaluates
// its graph, for every materials.glsl; and evaluateMaterialAtShadowHit, a switch over those
// materials' graphs alone, for the switch dispatch's materials.glsl and the wavefront's
// shadow pass (shadowSource, which also holds their includes). A switch of its own keeps the
// other graphs out of the shadow ray's code: the shader compiler inlines every call.
// materialStochasticOpacity, which says of a scene material whether a path's trace evaluates
// its opacity at a hit (stochastic_opacity.glsl), for every materials.glsl.

// A GLSL function `bool NAME(uint materialId)` that is true for the scene materials whose
// member `flag` is set, after the comment `comment` (lines of `// `).
std::string materialFlagTable(const std::vector<LinkedMaterial>& materials, const char* name,
                              const char* comment, bool LinkedMaterial::*flag) {
  std::string out =
      std::string(comment) + "bool " + name + "(uint materialId) {\n  switch (materialId) {\n";
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].*flag)
      out += "    case " + std::to_string(i) + "u:\n";
  return out + "      return true;\n    default:\n      return false;\n  }\n}\n";
}

std::string stochasticOpacityTable(const std::vector<LinkedMaterial>& materials) {
  return materialFlagTable(
      materials, "materialStochasticOpacity",
      "// Whether a path that hits scene material `materialId` evaluates its opacity in the\n"
      "// trace (it may write one below 1); it stops at any other.\n",
      &LinkedMaterial::stochasticOpacity);
}

std::string transparentShadowTable(const std::vector<LinkedMaterial>& materials) {
  return materialFlagTable(
      materials, "materialTransparentShadow",
      "// Whether a shadow ray that hits scene material `materialId` evaluates its graph (it\n"
      "// writes a Transparent lobe or an opacity below 1); it stops at any other.\n",
      &LinkedMaterial::transparentShadow);
}

// `void function(uint materialId, MaterialInputs inputs, out MaterialOutputs outputs)`: a switch
// that calls the graph of each scene material `wanted` picks, with its first texture slot, and
// gives any other material the default outputs.
template <typename Predicate>
std::string materialSwitch(const std::string& function,
                           const std::vector<LinkedMaterial>& materials, Predicate wanted) {
  std::string out = "void " + function +
                    "(uint materialId, MaterialInputs inputs, out MaterialOutputs outputs) {\n"
                    "  switch (materialId) {\n";
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const LinkedMaterial& m = materials[i];
    if (!wanted(m))
      continue;
    out += "    case " + std::to_string(i) +
           "u:\n      inputs.textureBase = " + std::to_string(m.textureBase) +
           ";\n      EvaluateMaterial_" + m.name + "(inputs, outputs);\n      break;\n";
  }
  return out +
         "    default:\n      outputs = mg_defaultMaterialOutputs(inputs);\n      break;\n  }\n}\n";
}

std::string transparentShadowSwitch(const std::vector<LinkedMaterial>& materials) {
  return "// The outputs of maybe-transparent scene material `materialId` at a shadow ray's "
         "hit.\n" +
         materialSwitch("evaluateMaterialAtShadowHit", materials,
                        [](const LinkedMaterial& m) { return m.transparentShadow; });
}

std::string shadowMaterials(const LinkedMaterials& linked) {
  if (!linked.transparentShadows)
    return "";
  return "// Generated by memograph's material linker. Do not edit.\n" +
         includesOf(linked, [](const LinkedMaterial& m) { return m.transparentShadow; }) +
         transparentShadowSwitch(linked.materials);
}

}  // namespace

LinkedMaterials linkMaterials(const std::vector<MaterialRef>& materials,
                              const MaterialLinkOptions& options) {
  auto start = std::chrono::steady_clock::now();
  if (materials.empty())
    throw std::runtime_error("the scene has no materials; every instance needs one");

  compiler::Diagnostics libraryDiagnostics;
  auto library = nodes::loadNodeLibrary(options.nodeLibraryDirectory.string(), libraryDiagnostics);
  if (!library) {
    throw std::runtime_error("the node library has errors:\n" +
                             compiler::formatDiagnostics(libraryDiagnostics));
  }

  LinkedMaterials linked;
  std::string includes;
  // Graphs compiled once per distinct source text; their function name is the graph's.
  std::map<std::string, LinkedMaterial> bySource;
  std::map<std::string, std::string> sourceByName;
  compiler::CompileOptions compileOptions;
  compileOptions.emitGlsl = true;
  compileOptions.emitHlsl = false;
  compileOptions.reportShape = true;
  // Per distinct graph: its source and its shape, for the material instances.
  std::vector<compiler::SourceFile> distinctSources;
  std::vector<InstanceCandidate> candidates;
  for (const MaterialRef& material : materials) {
    compiler::SourceFile graph;
    std::filesystem::path baseDirectory;
    if (!material.graphText.empty()) {
      graph.path = material.graphPath.empty() ? "<" + material.name + ">" : material.graphPath;
      graph.text = material.graphText;
    } else if (!material.graphPath.empty()) {
      graph.path = material.graphPath;
      if (!std::filesystem::is_regular_file(material.graphPath))
        throw std::runtime_error("material '" + material.name + "': graph file '" +
                                 material.graphPath + "' not found");
      graph.text = readText(material.graphPath);
      baseDirectory = std::filesystem::path(material.graphPath).parent_path();
    } else {
      throw std::runtime_error("material '" + material.name +
                               "' has neither a graph file nor graph text");
    }

    auto known = bySource.find(graph.text);
    if (known != bySource.end()) {
      linked.materials.push_back(known->second);
      continue;
    }
    compiler::Diagnostics diagnostics;
    auto compiled = compiler::compileMaterial(graph, *library, compileOptions, diagnostics);
    if (!compiled) {
      throw std::runtime_error("material '" + material.name + "' does not compile:\n" +
                               compiler::formatDiagnostics(diagnostics));
    }
    const std::string& name = compiled->metadata.name;
    if (auto other = sourceByName.find(name); other != sourceByName.end()) {
      throw std::runtime_error("two different material graphs are both named '" + name +
                               "'; rename one (EvaluateMaterial_" + name + " must be unique)");
    }
    sourceByName[name] = graph.text;
    LinkedMaterial entry;
    entry.name = name;
    entry.textureBase = static_cast<int>(linked.texturePaths.size());
    entry.cacheable = compiled->metadata.cacheable;
    entry.inputsUsed = compiled->metadata.inputsUsed;
    if (std::any_of(entry.inputsUsed.begin(), entry.inputsUsed.end(),
                    [](const std::string& input) { return compiler::isObjectSpaceInput(input); }))
      linked.objectInputs = true;
    if (std::any_of(entry.inputsUsed.begin(), entry.inputsUsed.end(),
                    [](const std::string& input) { return compiler::isPathInput(input); }))
      linked.pathInputs = true;
    if (const auto& ao = compiled->metadata.ambientOcclusion) {
      linked.tracedInputs = true;
      entry.ambientOcclusionDistance = static_cast<float>(ao->distance);
      entry.ambientOcclusionSamples = ao->samples;
      entry.ambientOcclusionFlags = (ao->inside ? kAmbientOcclusionInside : 0u) |
                                    (ao->onlyLocal ? kAmbientOcclusionOnlyLocal : 0u);
    }
    if (const auto& bevel = compiled->metadata.bevel) {
      linked.tracedInputs = true;
      entry.bevelRadius = static_cast<float>(bevel->radius);
      entry.bevelSamples = bevel->samples;
    }
    for (const std::string& output : compiled->metadata.outputsWritten) {
      if (output == "specularTint" || output == "cyclesPrincipled")
        linked.cyclesPrincipled = true;
      if (output == "lobes")
        linked.bsdfLobes = true;
      if (output == "lobeNormals")
        linked.lobeNormals = true;
    }
    // The include defines a library function, under its MG_FN_ guard, only where the graph
    // calls it.
    if (compiled->glsl.find("#define MG_FN_PrincipledLayers_") != std::string::npos ||
        compiled->glsl.find("#define MG_FN_PrincipledBsdf_") != std::string::npos)
      linked.principledLayers = true;
    // ChooseShader: its graph may hold more lobes than fit, of which the chosen ones take the
    // slots of those of weight 0 (mg_addLobe under MG_CLOSURE_CHOICE).
    if (compiled->glsl.find("#define MG_FN_ChooseShader_") != std::string::npos)
      linked.closureChoice = true;
    // Likewise TransparentBsdf, the only node that adds a MG_LOBE_TRANSPARENT lobe
    // (nodes/bsdf.inc): Cycles decides a shader's transparent shadows from its graph too
    // (SD_HAS_TRANSPARENT_SHADOW), so only such graphs are evaluated at shadow hits.
    if (compiled->glsl.find("#define MG_FN_TransparentBsdf_") != std::string::npos) {
      entry.transparentShadow = true;
      linked.transparentShadows = true;
    }
    // An opacity below 1 is seen through by paths and shadow rays alike (Cycles expands a
    // Principled BSDF's Alpha into a Transparent BSDF: shader_nodes.cpp
    // PrincipledBsdfNode::expand); an opacity left at 1 costs nothing.
    if (compiled->metadata.opacityBelowOne) {
      entry.stochasticOpacity = true;
      entry.transparentShadow = true;
      linked.stochasticOpacity = true;
      linked.transparentShadows = true;
    }
    entry.textureCount = compiled->metadata.textures.size();
    entry.estimatedCost = compiled->metadata.estimatedCost;
    // A whole uv-only material's key is a uv texel: it is cached only with the uv domain.
    if (!(options.cacheKeyDomains & kCacheKeyUv))
      entry.cacheable = false;
    if (entry.cacheable) {
      entry.cacheOutputMask =
          cacheOutputMask(compiled->metadata.outputsWritten, &entry.cacheValueCount);
      linked.cacheValueCount = std::max(linked.cacheValueCount, entry.cacheValueCount);
    } else {
      // A cacheable material keeps its whole-output entry (today's images, every dispatch);
      // the others are keyed by their cut where the texel cache can (MG_CACHE_CUTS).
      entry.cutDomain = cacheCutDomain(compiled->metadata.cutDomain);
      entry.cutWidth = static_cast<std::uint32_t>(compiled->metadata.cutWidth);
      if (entry.cutDomain == gpu::kCacheCutNone || entry.cutWidth == 0 ||
          !(options.cacheKeyDomains & cacheKeyDomainOf(entry.cutDomain))) {
        entry.cutDomain = gpu::kCacheCutNone;
        entry.cutWidth = 0;
      } else {
        entry.cutCostShare = compiled->metadata.cutCostShare;
      }
      entry.cutKeyedByInstance = std::any_of(
          entry.inputsUsed.begin(), entry.inputsUsed.end(), [](const std::string& input) {
            return input == "objectRandom" || input == "objectLocation";
          });
      linked.cutValueCount = std::max(linked.cutValueCount, entry.cutWidth);
    }
    entry.restInShade = entry.cutDomain != gpu::kCacheCutNone &&
                        entry.ambientOcclusionSamples == 0 && entry.bevelSamples == 0;
    entry.distinctIndex = static_cast<std::uint32_t>(linked.distinct.size());
    for (const auto& texture : compiled->metadata.textures) {
      std::filesystem::path path(texture);
      if (path.is_relative() && !baseDirectory.empty())
        path = baseDirectory / path;
      linked.texturePaths.push_back(path.string());
    }
    std::string include =
        "// ---- material " + name + " (" + graph.path + ")\n" + compiled->glsl + "\n";
    includes += include;
    linked.distinct.push_back({name, std::move(include), entry.textureBase, entry.cutWidth,
                               entry.cacheable, entry.restInShade});
    // A shared pass takes its defines from its first member, so what sets them joins the shape.
    candidates.push_back({compiled->shape + "\n// cacheable " + std::to_string(entry.cacheable) +
                              ", cut " + std::to_string(entry.cutWidth) + ", rest in shade " +
                              std::to_string(entry.restInShade) + "\n",
                          std::move(compiled->floatConstants)});
    distinctSources.push_back(graph);
    bySource.emplace(graph.text, entry);
    linked.materials.push_back(entry);
  }

  for (InstanceGroup& group : groupMaterialInstances(candidates)) {
    const DistinctMaterial& first = linked.distinct[group.members.front()];
    MaterialInstanceGroup shared{first.name, first.include, std::move(group)};
    if (shared.instances.parameterCount > 0) {
      compiler::CompileOptions parameterOptions = compileOptions;
      parameterOptions.reportShape = false;
      parameterOptions.parameterConstants = shared.instances.parameterConstants;
      compiler::Diagnostics diagnostics;
      const auto& source = distinctSources[shared.instances.members.front()];
      auto compiled = compiler::compileMaterial(source, *library, parameterOptions, diagnostics);
      if (!compiled) {
        throw std::runtime_error("material '" + first.name +
                                 "' does not compile with parameters:\n" +
                                 compiler::formatDiagnostics(diagnostics));
      }
      shared.include = "// ---- material " + first.name + " and its instances (" + source.path +
                       ")\n" + compiled->glsl + "\n";
    }
    linked.instanceGroups.push_back(std::move(shared));
  }

  std::string& out = linked.source;
  out = "// Generated by memograph's material linker. Do not edit.\n";
  out += "#ifndef MG_MATERIALS_GLSL\n#define MG_MATERIALS_GLSL\n";
  // The prelude (MaterialInputs, float3_D, ...) arrives, guarded, with each include.
  out += includes;
  out +=
      "// Evaluates the graph of scene material `materialId` (thesis §5.2: branch by material).\n";
  out += materialSwitch("evaluateMaterialSwitch", linked.materials,
                        [](const LinkedMaterial&) { return true; });
  out += "#endif\n";

  // The callable dispatch's raygen sees no material, only the types they exchange. The
  // guard is the emitter's, so a material include after it does not repeat the prelude.
  linked.preludeSource = "// Generated by memograph's material linker. Do not edit.\n";
  linked.preludeSource += "#ifndef MG_PRELUDE_GLSL\n#define MG_PRELUDE_GLSL\n";
  linked.preludeSource += library->prelude(compiler::Target::Glsl);
  linked.preludeSource += "#endif  // MG_PRELUDE_GLSL\n";

  // Texel cache (thesis §5.3.2): per scene material its output mask (0: never cached) and
  // ID0, ID1 of eq. 5.8-5.9, two independent hashes of its distinct graph (materials
  // sharing a graph and its textures share entries).
  std::string cacheInfo = "// Texel cache: x output mask (0: not cacheable), y ID0, z ID1.\n";
  cacheInfo += "const uvec4 mg_materialCacheInfo[" + std::to_string(linked.materials.size()) +
               "] = uvec4[](\n";
  for (std::size_t i = 0; i < linked.materials.size(); ++i) {
    const LinkedMaterial& m = linked.materials[i];
    std::uint32_t id0 = pcgHash(m.distinctIndex * 2u + 0x3c6ef372u);
    std::uint32_t id1 = pcgHash(pcgHash(m.distinctIndex * 2u + 1u) ^ 0xa54ff53au);
    cacheInfo += "    uvec4(" + std::to_string(m.cacheOutputMask) + "u, " + std::to_string(id0) +
                 "u, " + std::to_string(id1) + "u, 0u)" +
                 (i + 1 < linked.materials.size() ? ",\n" : ");\n");
  }
  if (linked.tracedInputs) {
    const std::string tracedInfo = tracedInputTables(linked.materials);
    out.insert(out.rfind("#endif"), tracedInfo);
    linked.preludeSource.insert(linked.preludeSource.rfind("#endif"), tracedInfo);
  }
  out.insert(out.rfind("#endif"), cacheInfo);
  out.insert(out.rfind("#endif"), cutInfoTable(linked.materials));
  out.insert(out.rfind("#endif"), cutSwitches(linked.materials));
  linked.preludeSource.insert(linked.preludeSource.rfind("#endif"), cacheInfo);
  linked.preludeSource.insert(linked.preludeSource.rfind("#endif"), cutInfoTable(linked.materials));
  linked.shadeRestSource = shadeRests(linked);
  if (linked.transparentShadows) {
    std::string table = transparentShadowTable(linked.materials);
    if (linked.stochasticOpacity)
      table += stochasticOpacityTable(linked.materials);
    out.insert(out.rfind("#endif"), table + transparentShadowSwitch(linked.materials));
    linked.preludeSource.insert(linked.preludeSource.rfind("#endif"), table);
  }
  linked.shadowSource = shadowMaterials(linked);
  linked.compileMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return linked;
}

#endif  // MG_HAVE_COMPILER

}  // namespace memograph::runtime
