#include "compiler/compiler.h"

#include "compiler/conversions.h"
#include "compiler/cut.h"
#include "compiler/emitter.h"
#include "compiler/lobe_budget.h"
#include "compiler/metadata.h"
#include "compiler/parser.h"
#include "compiler/resolved_graph.h"
#include "compiler/schedule.h"
#include "compiler/traced_inputs.h"
#include "compiler/type_inference.h"

namespace memograph::compiler {

namespace {

// Everything the passes before emission produce. Not movable: `resolved` points into
// `graph`.
struct Analysis {
  Graph graph;
  std::optional<ResolvedGraph> resolved;
  std::optional<std::vector<std::size_t>> order;
  std::optional<OverloadChoice> chosen;
  std::optional<AmbientOcclusionSettings> ambientOcclusion;
  std::optional<BevelSettings> bevel;

  Analysis() = default;
  Analysis(const Analysis&) = delete;
  Analysis& operator=(const Analysis&) = delete;

  bool run(const SourceFile& file, const NodeLibrary& library, Diagnostics& diagnostics) {
    const std::size_t errorsBefore = diagnostics.errorCount();
    graph = parseGraph(file, diagnostics);
    if (diagnostics.errorCount() > errorsBefore)
      return false;
    resolved = resolveGraph(graph, file, library, diagnostics);
    if (!resolved)
      return false;
    order = scheduleGraph(*resolved, file, diagnostics);
    if (!order)
      return false;
    chosen = inferTypes(*resolved, *order, file, diagnostics);
    if (!chosen)
      return false;
    const std::size_t errorsBeforeSettings = diagnostics.errorCount();
    ambientOcclusion = collectAmbientOcclusionSettings(*resolved, *order, file, diagnostics);
    bevel = collectBevelSettings(*resolved, *order, file, diagnostics);
    checkLobeBudget(*resolved, *order, file, diagnostics);
    return diagnostics.errorCount() == errorsBeforeSettings;
  }

  Type outputType(std::size_t node, std::size_t socket) const {
    return resolved->nodes[node].type->overloads[*(*chosen)[node]].socketTypes[socket];
  }
};

}  // namespace

std::optional<CompiledMaterial> compileMaterial(const SourceFile& file, const NodeLibrary& library,
                                                const CompileOptions& options,
                                                Diagnostics& diagnostics) {
  Analysis analysis;
  if (!analysis.run(file, library, diagnostics))
    return std::nullopt;
  CompiledMaterial result;
  const MaterialCut cut = findCut(*analysis.resolved, *analysis.order, *analysis.chosen);
  result.metadata = collectMetadata(*analysis.resolved, *analysis.order, *analysis.chosen, cut);
  result.metadata.ambientOcclusion = analysis.ambientOcclusion;
  result.metadata.bevel = analysis.bevel;
  result.metadataJson = metadataToJson(result.metadata);
  const EmitInput emitInput{*analysis.resolved, *analysis.order,
                            *analysis.chosen,   library,
                            result.metadata,    cut,
                            file.path,          options.parameterConstants};
  for (auto& constant : floatConstantInputs(emitInput))
    result.floatConstants.push_back(std::move(constant.floats));
  if (options.reportShape)
    result.shape = materialShape(emitInput, "Shape");
  if (options.emitGlsl)
    result.glsl = emitMaterial(emitInput, Target::Glsl);
  if (options.emitHlsl)
    result.hlsl = emitMaterial(emitInput, Target::Hlsl);
  return result;
}

std::optional<CheckReport> checkMaterial(const SourceFile& file, const NodeLibrary& library,
                                         Diagnostics& diagnostics) {
  Analysis analysis;
  if (!analysis.run(file, library, diagnostics))
    return std::nullopt;
  const auto& graph = *analysis.resolved;
  CheckReport report;
  report.metadata = collectMetadata(graph, *analysis.order, *analysis.chosen,
                                    findCut(graph, *analysis.order, *analysis.chosen));
  report.metadata.ambientOcclusion = analysis.ambientOcclusion;
  report.metadata.bevel = analysis.bevel;
  for (const std::size_t node : *analysis.order) {
    const auto& resolved = graph.nodes[node];
    const auto& type = *resolved.type;
    report.nodes.push_back(overloadSignature(type, type.overloads[*(*analysis.chosen)[node]]));
    for (std::size_t s = 0; s < type.sockets.size(); ++s) {
      if (type.sockets[s].direction != Direction::Out)
        continue;
      LinkReport link;
      const Type produced = analysis.outputType(node, s);
      link.name =
          resolved.outputLinks[s] ? "link" + std::to_string(*resolved.outputLinks[s]) : "(unused)";
      link.producer = type.name + "." + type.sockets[s].name;
      link.location = resolved.source->location;
      link.type = produced.name();
      link.derivatives = produced.derivatives;
      for (const auto& consumer : resolved.consumers[s]) {
        if (!(*analysis.chosen)[consumer.node])
          continue;
        const auto& consumerType = *graph.nodes[consumer.node].type;
        const Type wanted =
            consumerType.overloads[*(*analysis.chosen)[consumer.node]].socketTypes[consumer.socket];
        std::string text = consumerType.name + "." + consumerType.sockets[consumer.socket].name;
        if (wanted != produced)
          text += " (as " + wanted.name() + ")";
        link.consumers.push_back(text);
      }
      report.links.push_back(std::move(link));
    }
  }
  return report;
}

}  // namespace memograph::compiler
