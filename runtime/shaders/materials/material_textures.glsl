// The material graphs' texture access, shared by the path tracer (switch dispatch) and every
// material callable shader: one binding of the shared descriptor set, so a callable samples
// exactly the textures the switch would. The host defines MG_TEXTURE_COUNT.
#ifndef MG_MATERIAL_TEXTURES_GLSL
#define MG_MATERIAL_TEXTURES_GLSL
layout(set = 0, binding = kBindingTextures) uniform sampler2D textures[MG_TEXTURE_COUNT];

// Declared by the node prelude: mip level from the ray-cone derivatives (thesis §2.2),
// texture chosen per lane.
vec4 mg_SampleTexture(int textureIndex, vec2 uv, vec2 ddx, vec2 ddy) {
  int index = clamp(textureIndex, 0, MG_TEXTURE_COUNT - 1);
  return textureGrad(textures[nonuniformEXT(index)], uv, ddx, ddy);
}
#endif
