// Builds the triangle meshes of the built-in scenes: boxes, heightfields, simple solids.
// Every mesh gets unit normals and UVs in world units (so a graph's texture scale means the
// same on every object). The append* functions leave tangents alone: call computeTangents
// once the mesh is complete.
#pragma once

#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace memograph::runtime {

// UVs are world distance divided by this (metres per UV unit): 1 means one texture repeat
// per metre. Box faces are unwrapped one by one, each face's UV origin at its corner.
struct UvScale {
  float metresPerUnit = 1.0f;
};

// Appends an axis-aligned box spanning [minCorner, maxCorner] to `mesh` (24 vertices, flat
// faces, outward normals).
void appendBox(Mesh& mesh, glm::vec3 minCorner, glm::vec3 maxCorner, UvScale uv = {});

// A grid of (cells+1)^2 vertices over [x0,x1]×[z0,z1] with y = height(x, z); normals from
// central differences of `height`, UV = (x, z) / metresPerUnit; tangents computed.
Mesh makeHeightfield(std::string name, float x0, float z0, float x1, float z1, int cells,
                     const std::function<float(float, float)>& height, UvScale uv = {});

// A capped cylinder along +y from y=0 to y=height (trunks, posts); UV u around, v up.
void appendCylinder(Mesh& mesh, glm::vec3 base, float radius, float height, int segments,
                    UvScale uv = {});

// A cone along +y with its base at `base` (tree canopies).
void appendCone(Mesh& mesh, glm::vec3 base, float radius, float height, int segments,
                UvScale uv = {});

// A sphere of `rings`×`segments` quads whose radius is scaled per vertex by
// `radiusScale(unitDirection)` (rocks); UV from a latitude-longitude unwrap.
void appendDeformedSphere(Mesh& mesh, glm::vec3 centre, glm::vec3 radii, int rings, int segments,
                          const std::function<float(glm::vec3)>& radiusScale, UvScale uv = {});

// Recomputes smooth per-vertex normals as area-weighted sums of the face normals.
void computeNormals(Mesh& mesh);

// Recomputes per-vertex tangents from positions, UVs and normals (per-triangle dP/du
// accumulated, then Gram-Schmidt against the normal; w is the handedness of the frame).
// Leaves `tangents` empty when the mesh has no UVs.
void computeTangents(Mesh& mesh);

}  // namespace memograph::runtime
