// The members of the prelude's MaterialInputs and MaterialOutputs that nodes may annotate
// (`@input`, `@output`), in declaration order: one list for the library loader, which
// validates annotations, and for the metadata, which reports them in this order.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <string_view>

namespace memograph::compiler {

inline constexpr std::array<std::string_view, 23> kMaterialInputNames = {"uv",
                                                                         "position",
                                                                         "normal",
                                                                         "tangent",
                                                                         "vertexColor",
                                                                         "view",
                                                                         "time",
                                                                         "generated",
                                                                         "objectPosition",
                                                                         "geometricNormal",
                                                                         "objectNormal",
                                                                         "objectLocation",
                                                                         "objectRandom",
                                                                         "backfacing",
                                                                         "rayFlags",
                                                                         "rayLength",
                                                                         "rayDepth",
                                                                         "diffuseDepth",
                                                                         "glossyDepth",
                                                                         "transmissionDepth",
                                                                         "closureSeed",
                                                                         "ambientOcclusion",
                                                                         "bevelNormal"};

// The object-space inputs (Blender's Texture Coordinate, Geometry and Object Info): the
// members from `generated` up to the path state, which the prelude leaves out under
// MG_OMIT_OBJECT_INPUTS.
inline constexpr std::size_t kFirstObjectSpaceInput = 7;
static_assert(kMaterialInputNames[kFirstObjectSpaceInput] == "generated");

// The path-state inputs (Blender's Light Path node, and ChooseShader's per-hit random word):
// the members from `rayFlags` on, which the prelude leaves out under MG_OMIT_PATH_INPUTS.
inline constexpr std::size_t kFirstPathInput = 14;
static_assert(kMaterialInputNames[kFirstPathInput] == "rayFlags");

inline bool isObjectSpaceInput(std::string_view name) {
  const auto first = kMaterialInputNames.begin() + kFirstObjectSpaceInput;
  const auto last = kMaterialInputNames.begin() + kFirstPathInput;
  return std::find(first, last, name) != last;
}

// The traced inputs (docs/design/traced-inputs.md: Ambient Occlusion, Bevel): the members
// from `ambientOcclusion` on, filled by rays the path tracer traces from the hit before the graph
// runs; the prelude leaves them out under MG_OMIT_TRACED_INPUTS.
inline constexpr std::size_t kFirstTracedInput = 21;
static_assert(kMaterialInputNames[kFirstTracedInput] == "ambientOcclusion");

inline bool isPathInput(std::string_view name) {
  const auto first = kMaterialInputNames.begin() + kFirstPathInput;
  const auto last = kMaterialInputNames.begin() + kFirstTracedInput;
  return std::find(first, last, name) != last;
}

inline bool isTracedInput(std::string_view name) {
  const auto first = kMaterialInputNames.begin() + kFirstTracedInput;
  return std::find(first, kMaterialInputNames.end(), name) != kMaterialInputNames.end();
}

// `lobes`: the BSDF lobes that the BSDF sinks add (nodes/bsdf.inc; docs/design/closures.md);
// `lobeNormals`: some lobe has a normal of its own (a sink's Normal or ClearcoatNormal given),
// carried in MaterialOutputs::lobeParameters z, w.
inline constexpr std::array<std::string_view, 11> kMaterialOutputNames = {
    "baseColor", "metallic", "roughness", "specular", "specularTint", "cyclesPrincipled",
    "normal",    "emission", "opacity",   "lobes",    "lobeNormals"};

}  // namespace memograph::compiler
