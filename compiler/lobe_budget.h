// The lobe budget: how many BSDF lobes, and how many sets of Principled outputs, a graph's
// sinks can write at one hit (docs/design/closures.md, "Choosing a shader per hit"). A hit
// holds MG_MAX_LOBES lobes (mg_addLobe drops one more) and one set of Principled outputs (a
// second would overwrite the first); ChooseShader makes the sinks of its unchosen side add
// lobes of weight 0, which give their slots up, so a graph may hold more sinks than fit as
// long as no one choice of every ChooseShader leaves more than fit. This pass checks it.
#pragma once

#include <cstddef>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/resolved_graph.h"
#include "compiler/source_file.h"

namespace memograph::compiler {

// MG_MAX_LOBES of nodes/prelude/common.inc.
inline constexpr int kMaxLobes = 4;

// The most lobes and Principled-output sets the graph's sinks (in `order`) write at one hit.
struct LobeBudget {
  int lobes = 0;
  int principledSets = 0;
};

// The budget of a graph: a sink counts where its Weight may be above 0, which below a
// ChooseShader side (through MixShader weights and further choices) is only where that side
// is chosen; of a ChooseShader's two sides the larger counts. A sink whose Weight comes
// from anything else counts at every hit.
LobeBudget lobeBudget(const ResolvedGraph& graph, const std::vector<std::size_t>& order);

// Reports an error when the graph's budget exceeds kMaxLobes lobes or one Principled-output
// set; returns false then.
bool checkLobeBudget(const ResolvedGraph& graph, const std::vector<std::size_t>& order,
                     const SourceFile& file, Diagnostics& diagnostics);

}  // namespace memograph::compiler
