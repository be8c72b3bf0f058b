
void EvaluateMaterial_RaySwitched(in MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float2 link1;
  float unused1_Fac;
  float3 link2;
  float link3;
  float unused2_IsShadowRay;
  float unused2_IsDiffuseRay;
  float unused2_IsGlossyRay;
  float unused2_IsSingularRay;
  float unused2_IsReflectionRay;
  float unused2_IsTransmissionRay;
  float unused2_RayLength;
  float link4;
  float unused2_DiffuseDepth;
  float unused2_GlossyDepth;
  float unused2_TransmissionDepth;
  float3 link5;
  float link6;
  float link7;
  UVInput(inputs, link1);
  mg_spec_NoiseTexture_Dimensions_2(mg_to_float3(link1), 0.0, 5.0, 2.0, 0.5, 2.0, 0.0, unused1_Fac, link2);
  LightPath(inputs, link3, unused2_IsShadowRay, unused2_IsDiffuseRay, unused2_IsGlossyRay, unused2_IsSingularRay, unused2_IsReflectionRay, unused2_IsTransmissionRay, unused2_RayLength, link4, unused2_DiffuseDepth, unused2_GlossyDepth, unused2_TransmissionDepth);
  Mix(link2, float3(1.0, 1.0, 1.0), link3, link5);
  BaseColorOutput(link5, outputs);
  Add(link4, 1.0, link6);
  Div(1.0, link6, link7);
  RoughnessOutput(link7, outputs);
}

// The values of RaySwitched that only uv space and constants determine: 1 value in 3 floats.
struct MaterialCut_RaySwitched {
  float v[3];
};

// Only the uv-space members of inputs reach the packed values; the others may hold
// placeholders.
void EvaluateMaterialCut_RaySwitched(in MaterialInputs inputs, out MaterialCut_RaySwitched cut) {
  float2 link1;
  float unused1_Fac;
  float3 link2;
  UVInput(inputs, link1);
  mg_spec_NoiseTexture_Dimensions_2(mg_to_float3(link1), 0.0, 5.0, 2.0, 0.5, 2.0, 0.0, unused1_Fac, link2);
  cut.v[0] = link2.x;
  cut.v[1] = link2.y;
  cut.v[2] = link2.z;
}

void EvaluateMaterialRest_RaySwitched(in MaterialInputs inputs, in MaterialCut_RaySwitched cut, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float3 link2 = float3(cut.v[0], cut.v[1], cut.v[2]);
  float link3;
  float unused2_IsShadowRay;
  float unused2_IsDiffuseRay;
  float unused2_IsGlossyRay;
  float unused2_IsSingularRay;
  float unused2_IsReflectionRay;
  float unused2_IsTransmissionRay;
  float unused2_RayLength;
  float link4;
  float unused2_DiffuseDepth;
  float unused2_GlossyDepth;
  float unused2_TransmissionDepth;
  float3 link5;
  float link6;
  float link7;
  LightPath(inputs, link3, unused2_IsShadowRay, unused2_IsDiffuseRay, unused2_IsGlossyRay, unused2_IsSingularRay, unused2_IsReflectionRay, unused2_IsTransmissionRay, unused2_RayLength, link4, unused2_DiffuseDepth, unused2_GlossyDepth, unused2_TransmissionDepth);
  Mix(link2, float3(1.0, 1.0, 1.0), link3, link5);
  BaseColorOutput(link5, outputs);
  Add(link4, 1.0, link6);
  Div(1.0, link6, link7);
  RoughnessOutput(link7, outputs);
}
