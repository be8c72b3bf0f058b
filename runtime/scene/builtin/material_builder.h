// A typed vocabulary over GraphWriter for the material recipes: one method per node of the
// node library that the recipes use. The node and socket names live only in
// material_builder.cpp, so a renamed node is a one-line fix.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "runtime/scene/builtin/graph_writer.h"

namespace memograph::runtime {

class MaterialBuilder {
 public:
  // `ambientOcclusionSamples` > 0: the base colour goes through an Ambient Occlusion node
  // (Blender's default Distance, 1) of that many samples; `bevelSamples` > 0: the normal is a
  // Bevel node's (Blender's default Radius, 0.05) of that many samples. Both traced inputs.
  explicit MaterialBuilder(std::string name, int ambientOcclusionSamples = 0, int bevelSamples = 0);

  // Inputs and arithmetic.
  GraphLink uv();  // float2 texture coordinates
  // (uv*scale + offset, 0) as a float3, the texture nodes' vector type.
  GraphLink transformUv(GraphLink uv, glm::vec2 scale, glm::vec2 offset);
  GraphLink multiply(GraphLink a, float b);
  GraphLink multiply(GraphLink a, GraphLink b);
  GraphLink add(GraphLink a, float b);
  GraphLink fraction(GraphLink a);
  // 0 below `from0`, 1 above `from1`, linear between: turns noise into a mask.
  GraphLink mapRange(GraphLink value, float from0, float from1);

  // Procedural textures (Blender's definitions: Scale is features per UV unit, Detail the
  // number of octaves, Roughness the per-octave amplitude falloff).
  GraphLink noise(GraphLink vector, float scale, int detail, float roughness = 0.5f);
  GraphLink noiseColor(GraphLink vector, float scale, int detail, float roughness = 0.5f);
  GraphLink voronoiDistance(GraphLink vector, float scale);
  GraphLink voronoiColor(GraphLink vector, float scale);
  GraphLink checker(GraphLink vector, float scale);
  GraphLink brick(GraphLink vector, float scale, float mortarSize);  // 1 in the mortar

  // Colour and blending.
  // Maps fac ∈ [p0, p1] to c0 … c1 (constant outside), like a two-stop Blender ColorRamp.
  GraphLink ramp(GraphLink fac, float p0, glm::vec3 c0, float p1, glm::vec3 c1);
  GraphLink mix(GraphLink fac, GraphLink a, GraphLink b);  // a at fac 0, b at fac 1
  GraphLink mix(GraphLink fac, glm::vec3 a, glm::vec3 b);
  GraphLink mix(GraphLink fac, GraphLink a, glm::vec3 b);
  GraphLink mix(GraphLink fac, float a, float b);

  // Graph outputs (BRDF parameters).
  void baseColor(GraphLink color);
  void baseColor(glm::vec3 color);
  void roughness(GraphLink value);
  void roughness(float value);
  void metallic(GraphLink value);
  void metallic(float value);
  void emission(glm::vec3 radiance);

  std::string text() const { return graph_.text(); }

 private:
  GraphWriter graph_;
  int ambientOcclusionSamples_ = 0;
  // The base colour, through the Ambient Occlusion node where there is one.
  void baseColorOutput(GraphArg color);
};

}  // namespace memograph::runtime
