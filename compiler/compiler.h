// The compiler's front door: one .mgraph source in, GLSL/HLSL includes and metadata out.
// Runs the passes of thesis §5.1 in order: parse → resolve → prune/order → infer → emit.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/node_library.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

struct CompileOptions {
  bool emitGlsl = true;
  bool emitHlsl = true;
  // Material instances (docs/design/wavefront.md#material-instances): the float constant
  // inputs, by their index in CompiledMaterial::floatConstants, that the code reads from the
  // material's parameter block instead of writing them as literals. MG_MATERIAL_PARAMETER(k)
  // is float k of the block, which holds the chosen constants' floats in index order; the
  // including shader defines it. Empty (or all false): every constant a literal.
  std::vector<bool> parameterConstants;
  // Fill CompiledMaterial::shape.
  bool reportShape = false;
};

// Cycles' AO node settings (svm_node_ao): rays of length `distance` (0: none traced, the
// input is 1) about the shading normal, `samples` of them; `inside` traces into the object
// (the normal flipped), `onlyLocal` lets only the hit's own object occlude.
struct AmbientOcclusionSettings {
  double distance = 1.0;
  std::uint32_t samples = 16;
  bool inside = false;
  bool onlyLocal = false;
  bool operator==(const AmbientOcclusionSettings&) const = default;
};

// Cycles' Bevel node settings (svm_node_bevel): `samples` disk rays within `radius` of the
// hit (0: none traced, the input is the shading normal), whose hits' normals are averaged.
struct BevelSettings {
  double radius = 0.05;
  std::uint32_t samples = 4;
  bool operator==(const BevelSettings&) const = default;
};

// What the runtime needs to know about a material without reading its code.
struct MaterialMetadata {
  std::string name;
  std::vector<std::string> inputsUsed;      // members of MaterialInputs read: "uv", "normal", …
  std::vector<std::string> outputsWritten;  // members of MaterialOutputs written
  std::vector<std::string> textures;        // texture paths, in slot order
  // Outputs depend only on uv and constants, so they may be memoized (thesis §4.2).
  bool cacheable = false;
  bool needsDerivatives = false;  // some edge carries derivatives
  std::size_t nodeCount = 0;      // nodes after pruning
  // The part of the graph one cache key determines (compiler/cut.h): its key domain ("uv",
  // "object", "world", or "none" when no part is worth caching and no cut/rest functions are
  // emitted), the floats its values take, and the share of the graph's estimated cost it
  // holds (0..1; the per-node costs are uncalibrated estimates). `cacheable` stays the
  // whole-graph, uv-only test the runtime's caches use.
  std::string cutDomain = "none";
  std::size_t cutWidth = 0;
  double cutCostShare = 0.0;
  // The whole graph's estimated cost in the same units (cut.h's per-node estimates, an
  // overload with derivatives three times its plain one): weighs the material among others.
  double estimatedCost = 0.0;
  // The graph reads the traced input `ambientOcclusion` (compiler/traced_inputs.h): the
  // rays the path tracer traces for it before the graph runs. Nothing: no rays.
  std::optional<AmbientOcclusionSettings> ambientOcclusion;
  // Likewise `bevelNormal` (Blender's Bevel node): its rays' settings.
  std::optional<BevelSettings> bevel;
  // The graph writes an opacity that may be below 1 (an opacity sink whose Alpha or In is
  // linked or a constant below 1): the runtime lets paths and shadow rays pass its surface
  // (docs/design/closures.md, "Alpha"). A sink left at its default of 1 is opaque.
  bool opacityBelowOne = false;
};

struct CompiledMaterial {
  MaterialMetadata metadata;
  std::string glsl;  // empty unless CompileOptions::emitGlsl
  std::string hlsl;  // empty unless CompileOptions::emitHlsl
  std::string metadataJson;
  // The graph's float constant inputs (float to float4 sockets, with or without derivatives;
  // not tables, ints or textures) in emission order, node by node and socket by socket: each
  // as the floats its socket takes (a number splat to the socket's width).
  std::vector<std::vector<float>> floatConstants;
  // With CompileOptions::reportShape: the material's GLSL functions with every float
  // constant a parameter and a placeholder for its name. Graphs of one shape differ only in
  // their float constants, so one compiled shader serves them all (material instances).
  std::string shape;
};

// One link of a checked graph: what `memograph check` prints.
struct LinkReport {
  std::string name;         // "link3", or "unused…" for an output nothing reads
  std::string producer;     // "Mul.Out"
  SourceLocation location;  // of the producing node
  std::string type;         // "float3_D"
  bool derivatives = false;
  std::vector<std::string> consumers;  // "Add.B (mg_to_float3)" when converted
};

struct CheckReport {
  MaterialMetadata metadata;
  std::vector<std::string> nodes;  // chosen overload per node, in emission order
  std::vector<LinkReport> links;   // in emission order
};

// Runs every pass but emission and reports the inferred types.
std::optional<CheckReport> checkMaterial(const SourceFile& graph, const NodeLibrary& library,
                                         Diagnostics& diagnostics);

// Returns nothing when `diagnostics` gained an error. Warnings may be added either way.
std::optional<CompiledMaterial> compileMaterial(const SourceFile& graph, const NodeLibrary& library,
                                                const CompileOptions& options,
                                                Diagnostics& diagnostics);

}  // namespace memograph::compiler
