// Shared pieces of the runtime tests: a renderer on the test machine's ray-tracing device
// with validation on when installed, tiny scenes, and the material graphs they use (real
// .mgraph text compiled by the compiler against its test node library).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/renderer.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime::testing {

// Options for tests: the given backend, validation when the layer exists, a shader cache in
// a temporary folder, the compiler's test node library. Sets XDG_RUNTIME_DIR when unset.
RendererOptions testOptions(Backend backend = Backend::Auto);

// A square in the y = 0 plane (normal +y) of side `size`, UVs 0..uvScale across it.
Mesh quad(float size, float uvScale = 1.0f);

// A texture whose every texel is `color`, with levels of 4, 2 and 1 texels a side (so that
// textureGrad picks a mip).
TextureImage flatTexture(glm::vec3 color);
// A unit sphere (smooth normals, UVs from longitude/latitude).
Mesh sphere(int segments);
// A unit cube about the origin as one mesh (flat normals, outward counter-clockwise faces):
// Bevel looks only at its own instance, so the faces must not be instances of their own.
Mesh unitCube();

// Graph text of a material with a constant base color and roughness.
std::string constantGraph(const std::string& name, glm::vec3 baseColor, float roughness);

// The smallest scene that renders something: a 2 m quad of one grey material named
// `material` (constantGraph, roughness 0.5), seen from 3 m above it.
Scene greyQuadScene(const std::string& material = "Grey");

// Mean of channel `c` over the pixels in [x0,x1) x [y0,y1).
double meanChannel(const HdrImage& image, int c, int x0, int y0, int x1, int y1);

// Two renders of the same paths whose sums differ only in float rounding (a frame traced in
// several dispatches, each adding its share of the mean): the largest difference of any
// channel, and the reference's mean absolute value to judge it against. Sizes must match.
struct RoundingDifference {
  double largest = 0.0;        // over every channel
  double referenceMean = 0.0;  // the reference's mean colour channel (alpha left out)
};
RoundingDifference roundingDifference(const HdrImage& image, const HdrImage& reference);

// A `size`-texel square texture with `levels` mip levels, each its own red value
// (level / (levels - 1)) under a green checker of `period`-texel squares, so the red channel
// of a sample reads back the (blended) mip level it used.
TextureImage levelTaggedChecker(std::uint32_t size, int levels, std::uint32_t period);

}  // namespace memograph::runtime::testing
