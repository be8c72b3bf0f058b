// The floor run's material (MG_MATERIAL_FLOOR), shared by the megakernel (path_tracer.glsl)
// and the wavefront passes (wavefront.glsl) so that both shade the same free materials: every
// material replaced by constants, no graph evaluated, so the frame time is the path tracer's
// alone (what a free material would cost). Each material keeps a colour of its own (a hash of
// its id) so the image still tells materials apart. Needs rng.glsl (pcgHash).
void evaluateMaterialDirect(uint materialId, MaterialInputs inputs,
                            out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);  // geometric normal, no emission, opaque
  uint h = pcgHash(materialId ^ 0x9e3779b9u);
  outputs.baseColor = vec3(0.2) + 0.6 * vec3(uvec3(h, h >> 8u, h >> 16u) & 255u) / 255.0;
  outputs.roughness = 0.5;
  outputs.metallic = 0.0;
}
