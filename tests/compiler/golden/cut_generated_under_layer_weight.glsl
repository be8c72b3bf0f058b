
void EvaluateMaterial_GeneratedUnderLayerWeight(in MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float unused2_Fresnel;
  float link3;
  float3 link1;
  float3 unused0_Normal;
  float3 unused0_UV;
  float3 unused0_Object;
  float3 unused0_Reflection;
  float unused1_Fac;
  float3 link2;
  float3 link4;
  LayerWeight(0.5, float3(0.0, 0.0, 0.0), inputs, unused2_Fresnel, link3);
  TextureCoordinate(inputs, link1, unused0_Normal, unused0_UV, unused0_Object, unused0_Reflection);
  mg_spec_NoiseTexture_Dimensions_2(link1, 0.0, 5.0, 2.0, 0.5, 2.0, 0.0, unused1_Fac, link2);
  MixColor(link3, link2, float3(0.0, 0.0, 0.0), 0, 1, 0, 0, link4);
  BaseColorOutput(link4, outputs);
}

// The values of GeneratedUnderLayerWeight that only object space and constants determine: 1 value in 3 floats.
struct MaterialCut_GeneratedUnderLayerWeight {
  float v[3];
};

// Only the object-space members of inputs reach the packed values; the others may hold
// placeholders.
void EvaluateMaterialCut_GeneratedUnderLayerWeight(in MaterialInputs inputs, out MaterialCut_GeneratedUnderLayerWeight cut) {
  float3 link1;
  float3 unused0_Normal;
  float3 unused0_UV;
  float3 unused0_Object;
  float3 unused0_Reflection;
  float unused1_Fac;
  float3 link2;
  TextureCoordinate(inputs, link1, unused0_Normal, unused0_UV, unused0_Object, unused0_Reflection);
  mg_spec_NoiseTexture_Dimensions_2(link1, 0.0, 5.0, 2.0, 0.5, 2.0, 0.0, unused1_Fac, link2);
  cut.v[0] = link2.x;
  cut.v[1] = link2.y;
  cut.v[2] = link2.z;
}

void EvaluateMaterialRest_GeneratedUnderLayerWeight(in MaterialInputs inputs, in MaterialCut_GeneratedUnderLayerWeight cut, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float3 link2 = float3(cut.v[0], cut.v[1], cut.v[2]);
  float unused2_Fresnel;
  float link3;
  float3 link4;
  LayerWeight(0.5, float3(0.0, 0.0, 0.0), inputs, unused2_Fresnel, link3);
  MixColor(link3, link2, float3(0.0, 0.0, 0.0), 0, 1, 0, 0, link4);
  BaseColorOutput(link4, outputs);
}
