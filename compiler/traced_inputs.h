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

// The MaterialInputs member the AO node reads, and the node sockets that hold its settings.
inline constexpr std::string_view kAmbientOcclusionInput = "ambientOcclusion";

// The settings of the graph's nodes (in `order`) that read kAmbientOcclusionInput: nothing
// when none does. Reports an error (returning nothing) where a setting socket is linked
// rather than a constant, a setting is out of range, or two such nodes disagree (the tracer
// fills one value per hit).
std::optional<AmbientOcclusionSettings> collectAmbientOcclusionSettings(
    const ResolvedGraph& graph, const std::vector<std::size_t>& order, const SourceFile& file,
    Diagnostics& diagnostics);

}  // namespace memograph::compiler
