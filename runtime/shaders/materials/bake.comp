// `memograph bake` (docs/guide/bake.md): evaluates one material graph at the pixel centres of its
// UV square, one invocation per pixel, as if the graph were on Blender's default plane (or
// a plane spanning the given object bounds). The host provides "bake_material.glsl" (the
// compiler's GLSL include of the material) and defines MG_TEXTURE_COUNT and
// MG_BAKE_EVALUATE (the material's EvaluateMaterial_<Name>).
//
// Pixel (i, j) is at uv ((i + 0.5) / W, (j + 0.5) / H): row j = 0 is v near 0, Blender's
// img.pixels order (bottom row first). The values buffer is written in that order; the host
// turns it into files.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require

#include "shared_types.h"
#include "bake_material.glsl"
#include "material_textures.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MG_BAKE_TIMING
// `bake --time`: one float a pixel, the sum of every output component, so that no output is
// dead code while the stores stay a small fixed part of the time (four vec4 a pixel made an
// evaluation of a few arithmetic nodes bound by its memory traffic).
layout(set = 0, binding = 0, std430) writeonly buffer BakeSums {
  float bakeSums[];
};
#else
// Four vec4 a pixel: (baseColor, metallic), (normal, roughness), (emission, opacity),
// (specular, specularTint, cyclesPrincipled, 0).
layout(set = 0, binding = 0, std430) writeonly buffer BakeValues {
  vec4 bakeValues[];
};
#endif

layout(push_constant) uniform BakePush {
  vec4 boundsMin;  // xyz: the object's bounding box (object = world space here)
  vec4 boundsMax;
  vec4 normal;  // xyz: the shading normal (unit; the host normalizes it)
  uvec4 size;  // x width, y height
} bake;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uvec2 size = bake.size.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec2 texel = 1.0 / vec2(size);
  vec2 uv = (vec2(pixel) + 0.5) * texel;

  // The plane spans the bounds in x and y at the bounds' centre in z: Blender's default
  // plane (size 2) for the default bounds, (2u - 1, 2v - 1, 0).
  vec3 lo = bake.boundsMin.xyz;
  vec3 hi = bake.boundsMax.xyz;
  vec3 extent = hi - lo;
  vec3 position = vec3(lo.xy + uv * extent.xy, 0.5 * (lo.z + hi.z));
  // The footprint is Cycles' bake footprint, so that nodes that differentiate (Bump over a
  // procedural height, image mip selection) bake as Cycles bakes them: its compact
  // differential around the normal, two steps of half a texel along the diagonals
  // (1, -1, 0) and (1, 1, 0) (measured with Blender 3.4 at 32, 64 and 128 pixels).
  float halfTexel = 0.25 * (texel.x * extent.x + texel.y * extent.y);
  float k = halfTexel * 0.70710678;
  vec3 dPdx = vec3(k, -k, 0.0);
  vec3 dPdy = vec3(k, k, 0.0);
  // uv follows the plane's mapping (uv = (P.xy - lo.xy) / extent.xy); a flat bound keeps 0.
  vec2 toUv = mix(1.0 / max(extent.xy, vec2(1e-30)), vec2(0.0), equal(extent.xy, vec2(0.0)));
  // Blender's automatic texture space (BKE_mesh_texspace_calc; autoTextureSpace on the
  // host): the box centre and half extent, a zero size replaced by 1 and one below 1e-5
  // raised to 1e-5; Generated = (co - loc) / (2 size) + 0.5.
  vec3 loc = 0.5 * (lo + hi);
  vec3 halfSize = 0.5 * extent;
  halfSize = mix(max(halfSize, vec3(1e-5)), vec3(1.0), equal(halfSize, vec3(0.0)));
  vec3 toGenerated = 0.5 / halfSize;

  MaterialInputs inputs;
  inputs.uv.v = uv;
  inputs.uv.x = dPdx.xy * toUv;
  inputs.uv.y = dPdy.xy * toUv;
  inputs.position.v = position;
  inputs.position.x = dPdx;
  inputs.position.y = dPdy;
  inputs.normal = bake.normal.xyz;
  inputs.tangent = vec3(1.0, 0.0, 0.0);
  inputs.bitangentSign = vec3(1.0, 0.0, 0.0);
  inputs.vertexColor = vec4(1.0);
  inputs.view = vec3(0.0, 0.0, 1.0);
  inputs.time = 0.0;
  inputs.textureBase = 0;
  inputs.generated.v = (position - loc) * toGenerated + 0.5;
  inputs.generated.x = dPdx * toGenerated;
  inputs.generated.y = dPdy * toGenerated;
  inputs.generatedScale = toGenerated;
  inputs.objectPosition = inputs.position;
  inputs.geometricNormal = vec3(0.0, 0.0, 1.0);
  inputs.objectNormal = inputs.normal;  // the bake's object is untransformed
  inputs.objectLocation = vec3(0.0);
  inputs.objectRandom = 0.0;
  inputs.backfacing = 0.0;
  // Cycles' bake (integrator/init_from_bake.h): a camera path at depth 0 whose intersection
  // lies at t = 1 along a ray from one unit above the surface.
  inputs.rayFlags = MG_RAY_CAMERA;
  inputs.rayLength = 1.0;
  inputs.rayDepth = 0;
  inputs.diffuseDepth = 0;
  inputs.glossyDepth = 0;
  inputs.transmissionDepth = 0;
  inputs.closureSeed = 0u;
#ifndef MG_OMIT_TRACED_INPUTS
  // A bake traces nothing (Cycles' bake would trace AO against the scene; here no scene).
  inputs.ambientOcclusion = 1.0;
  inputs.bevelNormal = inputs.normal;
#endif

  MaterialOutputs outputs;
  MG_BAKE_EVALUATE(inputs, outputs);

#ifdef MG_BAKE_TIMING
  bakeSums[pixel.y * size.x + pixel.x] =
      dot(outputs.baseColor + outputs.normal + outputs.emission, vec3(1.0)) + outputs.metallic +
      outputs.roughness + outputs.opacity + outputs.specular + outputs.specularTint +
      outputs.cyclesPrincipled;
#else
  uint base = 4u * (pixel.y * size.x + pixel.x);
  bakeValues[base + 0u] = vec4(outputs.baseColor, outputs.metallic);
  bakeValues[base + 1u] = vec4(outputs.normal, outputs.roughness);
  bakeValues[base + 2u] = vec4(outputs.emission, outputs.opacity);
  bakeValues[base + 3u] =
      vec4(outputs.specular, outputs.specularTint, outputs.cyclesPrincipled, 0.0);
#endif
}
