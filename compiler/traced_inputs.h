// The settings of the material inputs the path tracer traces rays for before a graph runs
// (Blender's Ambient Occlusion node: docs/design/traced-inputs.md). A material cannot trace
// (callable shaders and the wavefront's material passes have no ray tracing), so a node
// that needs rays reads a per-hit MaterialInputs member the tracer fills, and its settings
// must be constants the runtime knows before the graph runs: this pass collects them.
#pragma once

#include <cstdint>
#include <optional>

#include "compiler/compiler.h"
#include "compiler/diagnostics.h"
#include "compiler/resolved_graph.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

// The MaterialInputs members the AO and Bevel nodes read; their settings are sockets of the
// nodes.
inline constexpr std::string_view kAmbientOcclusionInput = "ambientOcclusion";
inline constexpr std::string_view kBevelInput = "bevelNormal";

// The settings of the graph's nodes (in `order`) that read kAmbientOcclusionInput: nothing
// when none does. Reports an error (returning nothing) where a setting socket is linked
// rather than a constant, a setting is out of range, or two such nodes disagree (the tracer
// fills one value per hit).
std::optional<AmbientOcclusionSettings> collectAmbientOcclusionSettings(
    const ResolvedGraph& graph, const std::vector<std::size_t>& order, const SourceFile& file,
    Diagnostics& diagnostics);

}  // namespace memograph::compiler

namespace memograph::compiler {

// The settings of the graph's nodes that read kBevelInput (Radius >= 0, Samples 1..128), with
// the same errors as collectAmbientOcclusionSettings.
std::optional<BevelSettings> collectBevelSettings(const ResolvedGraph& graph,
                                                  const std::vector<std::size_t>& order,
                                                  const SourceFile& file, Diagnostics& diagnostics);

}  // namespace memograph::compiler
