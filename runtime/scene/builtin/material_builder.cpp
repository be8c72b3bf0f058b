#include "runtime/scene/builtin/material_builder.h"

// Node and socket names as declared in nodes/*.inc (docs/guide/nodes.md): math.inc (Mul, Add,
// Fract, MapRange, Mix), converter.inc (ColorRamp4), inputs.inc, outputs.inc, and the
// texture families (NoiseTexture, VoronoiTexture, CheckerTextureFiltered, BrickTexture).
namespace memograph::runtime {
namespace {
using A = GraphArg;
}  // namespace

MaterialBuilder::MaterialBuilder(std::string name, int ambientOcclusionSamples, int bevelSamples)
    : graph_(std::move(name)), ambientOcclusionSamples_(ambientOcclusionSamples) {
  if (bevelSamples > 0) {
    const GraphLink normal = graph_.newLink();
    graph_.node("Bevel", {A::constant("Radius", 0.05f),
                          A::constant("Samples", static_cast<float>(bevelSamples)),
                          A::out("Normal", normal)});
    graph_.node("NormalOutput", {A::in("In", normal)});
  }
}

void MaterialBuilder::baseColorOutput(GraphArg color) {
  if (ambientOcclusionSamples_ > 0) {
    const GraphLink occluded = graph_.newLink();
    color.socket = "Color";
    graph_.node("AmbientOcclusion",
                {color, A::constant("Distance", 1.0f),
                 A::constant("Samples", static_cast<float>(ambientOcclusionSamples_)),
                 A::out("Out", occluded)});
    graph_.node("BaseColorOutput", {A::in("In", occluded)});
    return;
  }
  color.socket = "In";
  graph_.node("BaseColorOutput", {color});
}

GraphLink MaterialBuilder::uv() {
  const GraphLink out = graph_.newLink();
  graph_.node("UVInput", {A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::transformUv(GraphLink uv, glm::vec2 scale, glm::vec2 offset) {
  const GraphLink scaled = graph_.newLink(), out = graph_.newLink();
  // Three components on purpose: the textures take float3 vectors, and widening the UV
  // once at the first node leaves the compiler no choice of where to widen it (with
  // float2 constants a UV feeding two textures is an ambiguous overload choice).
  graph_.node("Mul",
              {A::in("A", uv), A::constant("B", glm::vec3(scale, 1.0f)), A::out("Out", scaled)});
  graph_.node("Add",
              {A::in("A", scaled), A::constant("B", glm::vec3(offset, 0.0f)), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::multiply(GraphLink a, float b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mul", {A::in("A", a), A::constant("B", b), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::multiply(GraphLink a, GraphLink b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mul", {A::in("A", a), A::in("B", b), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::add(GraphLink a, float b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Add", {A::in("A", a), A::constant("B", b), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::fraction(GraphLink a) {
  const GraphLink out = graph_.newLink();
  graph_.node("Fract", {A::in("In", a), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::mapRange(GraphLink value, float from0, float from1) {
  const GraphLink out = graph_.newLink();
  graph_.node("MapRange",
              {A::in("In", value), A::constant("FromMin", from0), A::constant("FromMax", from1),
               A::constant("ToMin", 0.0f), A::constant("ToMax", 1.0f), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::noise(GraphLink vector, float scale, int detail, float roughness) {
  const GraphLink fac = graph_.newLink();
  graph_.node("NoiseTexture", {A::in("Vector", vector), A::constant("Scale", scale),
                               A::constant("Detail", static_cast<float>(detail)),
                               A::constant("Roughness", roughness), A::out("Fac", fac)});
  return fac;
}

GraphLink MaterialBuilder::noiseColor(GraphLink vector, float scale, int detail, float roughness) {
  const GraphLink color = graph_.newLink();
  graph_.node("NoiseTexture", {A::in("Vector", vector), A::constant("Scale", scale),
                               A::constant("Detail", static_cast<float>(detail)),
                               A::constant("Roughness", roughness), A::out("Color", color)});
  return color;
}

GraphLink MaterialBuilder::voronoiDistance(GraphLink vector, float scale) {
  const GraphLink distance = graph_.newLink();
  graph_.node("VoronoiTexture",
              {A::in("Vector", vector), A::constant("Scale", scale), A::out("Distance", distance)});
  return distance;
}

GraphLink MaterialBuilder::voronoiColor(GraphLink vector, float scale) {
  const GraphLink color = graph_.newLink();
  graph_.node("VoronoiTexture",
              {A::in("Vector", vector), A::constant("Scale", scale), A::out("Color", color)});
  return color;
}

GraphLink MaterialBuilder::checker(GraphLink vector, float scale) {
  const GraphLink fac = graph_.newLink();
  graph_.node("CheckerTextureFiltered",
              {A::in("Vector", vector), A::constant("Scale", scale), A::out("Fac", fac)});
  return fac;
}

GraphLink MaterialBuilder::brick(GraphLink vector, float scale, float mortarSize) {
  const GraphLink fac = graph_.newLink();
  graph_.node("BrickTexture", {A::in("Vector", vector), A::constant("Scale", scale),
                               A::constant("MortarSize", mortarSize), A::out("Fac", fac)});
  return fac;
}

GraphLink MaterialBuilder::ramp(GraphLink fac, float p0, glm::vec3 c0, float p1, glm::vec3 c1) {
  const GraphLink color = graph_.newLink();
  graph_.node("ColorRamp4",
              {A::in("Fac", fac), A::constant("Pos0", p0), A::constant("Color0", c0),
               A::constant("Pos1", p1), A::constant("Color1", c1), A::out("Color", color)});
  return color;
}

GraphLink MaterialBuilder::mix(GraphLink fac, GraphLink a, GraphLink b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mix", {A::in("A", a), A::in("B", b), A::in("Factor", fac), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::mix(GraphLink fac, glm::vec3 a, glm::vec3 b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mix",
              {A::constant("A", a), A::constant("B", b), A::in("Factor", fac), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::mix(GraphLink fac, GraphLink a, glm::vec3 b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mix",
              {A::in("A", a), A::constant("B", b), A::in("Factor", fac), A::out("Out", out)});
  return out;
}

GraphLink MaterialBuilder::mix(GraphLink fac, float a, float b) {
  const GraphLink out = graph_.newLink();
  graph_.node("Mix",
              {A::constant("A", a), A::constant("B", b), A::in("Factor", fac), A::out("Out", out)});
  return out;
}

void MaterialBuilder::baseColor(GraphLink color) {
  baseColorOutput(A::in("In", color));
}
void MaterialBuilder::baseColor(glm::vec3 color) {
  baseColorOutput(A::constant("In", color));
}
void MaterialBuilder::roughness(GraphLink value) {
  graph_.node("RoughnessOutput", {A::in("In", value)});
}
void MaterialBuilder::roughness(float value) {
  graph_.node("RoughnessOutput", {A::constant("In", value)});
}
void MaterialBuilder::metallic(GraphLink value) {
  graph_.node("MetallicOutput", {A::in("In", value)});
}
void MaterialBuilder::metallic(float value) {
  graph_.node("MetallicOutput", {A::constant("In", value)});
}
void MaterialBuilder::emission(glm::vec3 radiance) {
  graph_.node("EmissionOutput", {A::constant("Color", radiance), A::constant("Strength", 1.0f)});
}

}  // namespace memograph::runtime
