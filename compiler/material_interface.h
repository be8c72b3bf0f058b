// The members of the prelude's MaterialInputs and MaterialOutputs that nodes may annotate
// (`@input`, `@output`), in declaration order: one list for the library loader, which
// validates annotations, and for the metadata, which reports them in this order.
#pragma once

#include <array>
#include <string_view>

namespace memograph::compiler {

inline constexpr std::array<std::string_view, 13> kMaterialInputNames = {
    "uv",        "position",  "normal",         "tangent",         "vertexColor",    "view",
    "time",      "generated", "objectPosition", "geometricNormal", "objectLocation", "objectRandom",
    "backfacing"};

inline constexpr std::array<std::string_view, 9> kMaterialOutputNames = {
    "baseColor",        "metallic", "roughness", "specular", "specularTint",
    "cyclesPrincipled", "normal",   "emission",  "opacity"};

}  // namespace memograph::compiler
