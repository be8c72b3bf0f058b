// Variation analysis: over which domain each value of a material graph varies, so that the
// part of a graph that one cache key determines can be memoized (thesis §7: memoize
// well-suited subgraphs; the cut itself is in cut.h).
//
// The classes form a lattice. Constant is the bottom. The three key domains, Uv (texture
// space, the thesis's key, §4.2), Object (object space per instance) and World (world space,
// the voxel key of seed 002 §3.1-3.2), sit above it and are incomparable: a value that mixes
// two of them has no single key, so it is PerHit, like every value that is interpolated or
// depends on the ray (normal, tangent, vertexColor, view, backfacing, geometricNormal, and
// the path state that Light Path reads: rayFlags, rayLength and the depths).
// PerFrame (time) is the top: such a value changes every frame, so no frame can reuse
// another's entry whatever the key.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "compiler/resolved_graph.h"
#include "compiler/type_inference.h"

namespace memograph::compiler {

enum class Variation { Constant, Uv, Object, World, PerHit, PerFrame };

// "constant", "uv", "object", "world", "per-hit", "per-frame".
std::string_view variationName(Variation variation);

bool isKeyDomain(Variation variation);

// The least class above both.
Variation join(Variation a, Variation b);

// The class of one MaterialInputs member. The per-instance members (objectLocation,
// objectRandom) are Object: they are constant over an instance, and an object-space key
// names the instance (object-space coordinates alone would make two instances of one mesh
// share entries), so they add nothing the key does not already hold. textureBase and members
// a material may not annotate count as Constant.
Variation inputVariation(std::string_view member);

// The class of each output socket of each scheduled node: [node][socket] (input sockets and
// unscheduled nodes hold Constant). A node with linked inputs gives all its outputs the join
// of its inputs' classes and of the members it reads; a source node that reads members of
// several classes (Texture Coordinate, Geometry) gives each output the class of the member it
// copies (table in variation.cpp).
using SocketVariation = std::vector<std::vector<Variation>>;
SocketVariation analyseVariation(const ResolvedGraph& graph, const std::vector<std::size_t>& order);

// For tests: the node names and sockets whose class comes from the per-socket table, so a
// test can check the table against the library it describes.
struct SourceSocketClass {
  std::string_view node;
  std::string_view socket;
  Variation variation;
};
const std::vector<SourceSocketClass>& sourceSocketClasses();

}  // namespace memograph::compiler
