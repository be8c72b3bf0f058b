// Mesh LODs for culled renders (seeds/001 §3.3.1: one BLAS per mesh LOD, shared by the
// instances that show it; §3.3: LODs lower the memory of what stays in the TLAS far away).
// meshoptimizer's edge-collapse simplifier builds a chain of coarser meshes at scene
// creation, each bounded by an object-space error that the LOD choice projects to pixels
// (runtime/accel/lod_choice.h). The same mesh gives the same LODs on any machine.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

struct MeshLodSettings {
  // Each level's target error, as a fraction of the mesh's extent (meshopt_simplifyScale: the
  // largest side of its bounding box). On a city building (about 40 m) 0.25 %, 0.75 % and
  // 2.5 % are 0.1, 0.3 and 1 m: at 1920 x 1080 and a 40° field of view a pixel spans
  // 0.1 m at 150 m, so the levels come in at about 150, 450 and 1500 m, and at the small
  // renders' 270 rows four times nearer. The first level drops the window frames' inner
  // edges (they stand 0.18 m out), the last leaves the building's blocks.
  std::array<float, 3> relativeErrors{0.0025f, 0.0075f, 0.025f};
  // A mesh with fewer triangles gets no LODs: a BLAS of a few hundred triangles costs less
  // than what a second BLAS beside it would during a switch.
  std::size_t minTriangles = 256;
  // A level is kept only if it has at most this fraction of the finer level's triangles;
  // one that does not is skipped, and the next target tried from the same finer level.
  float maxTriangleFraction = 0.8f;
};

// The LODs of `mesh`, finest first (empty when none pays). Each level simplifies the one
// before it (welded by position, so that the faces of a box, split for their normals,
// collapse together), so its error is the sum of the passes' errors: a bound on the
// distance from the mesh's surface, in the mesh's units; and it records the longest part it
// (or a finer level) removed whole (MeshLod::removedPart), which the LOD choice counts as
// well: a window frame collapses within its thickness, 0.2 m, but what goes is 1.5 m long
// (on lavapipe, counting it took the small city's mirror view from an LDR-FLIP of 0.036 to
// 0.0065 against unculled at --lod-pixel-error 1). A level's corners take the
// attributes of the mesh's vertex at that position whose normal is nearest the simplified
// triangle's own, so flat faces keep their normals and uvs.
std::vector<MeshLod> buildMeshLods(const Mesh& mesh, const MeshLodSettings& settings = {});

// Gives the scene's listed meshes their LODs (Scene::meshLods; the others none).
void addMeshLods(Scene& scene, const std::vector<std::uint32_t>& meshes,
                 const MeshLodSettings& settings = {});

}  // namespace memograph::runtime
