
void EvaluateMaterial_BumpOverNoise(in MaterialInputs inputs, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float3_D link1;
  float3_D unused0_Normal;
  float3_D unused0_UV;
  float3_D unused0_Object;
  float3_D unused0_Reflection;
  float_D link2;
  float3_D unused1_Color;
  float3 link3;
  TextureCoordinate(inputs, link1, unused0_Normal, unused0_UV, unused0_Object, unused0_Reflection);
  mg_spec_NoiseTexture_Dimensions_2(link1, 0.0, 5.0, 3.0, 0.5, 2.0, 0.0, link2, unused1_Color);
  Bump(1.0, 1.0, link2, float3(0.0, 0.0, 0.0), 0, inputs, link3);
  NormalOutput(link3, outputs);
}

// The values of BumpOverNoise that only object space and constants determine: 1 value in 4 floats.
struct MaterialCut_BumpOverNoise {
  float v[4];
};

// Only the object-space members of inputs reach the packed values; the others may hold
// placeholders.
// Values with derivatives are packed with their gradient along the key space's axes,
// a finite difference over one key step: the footprint's shorter axis, which at a
// key is its texel's or voxel's size.
void EvaluateMaterialCut_BumpOverNoise(in MaterialInputs keyInputs, out MaterialCut_BumpOverNoise cut) {
  float keyStep = max(min(length(keyInputs.objectPosition.x), length(keyInputs.objectPosition.y)), 1.0e-5);
  for (int axisRun = 0; axisRun < 2; ++axisRun) {
    MaterialInputs inputs = keyInputs;
    inputs.objectPosition.x = float3(axisRun == 0 ? keyStep : 0.0, 0.0, axisRun == 1 ? keyStep : 0.0);
    inputs.objectPosition.y = float3(0.0, axisRun == 0 ? keyStep : 0.0, 0.0);
    inputs.generated.x = inputs.objectPosition.x * inputs.generatedScale;
    inputs.generated.y = inputs.objectPosition.y * inputs.generatedScale;
    float3_D link1;
    float3_D unused0_Normal;
    float3_D unused0_UV;
    float3_D unused0_Object;
    float3_D unused0_Reflection;
    float_D link2;
    float3_D unused1_Color;
    TextureCoordinate(inputs, link1, unused0_Normal, unused0_UV, unused0_Object, unused0_Reflection);
    mg_spec_NoiseTexture_Dimensions_2(link1, 0.0, 5.0, 3.0, 0.5, 2.0, 0.0, link2, unused1_Color);
    if (axisRun == 0) {
      cut.v[0] = link2.v;
      cut.v[1] = link2.x / keyStep;
      cut.v[2] = link2.y / keyStep;
    } else {
      cut.v[3] = link2.x / keyStep;
    }
  }
}

void EvaluateMaterialRest_BumpOverNoise(in MaterialInputs inputs, in MaterialCut_BumpOverNoise cut, out MaterialOutputs outputs) {
  outputs = mg_defaultMaterialOutputs(inputs);
  float_D link2 = mg_make_float_D(cut.v[0],
      cut.v[1] * inputs.objectPosition.x.x + cut.v[2] * inputs.objectPosition.x.y + cut.v[3] * inputs.objectPosition.x.z,
      cut.v[1] * inputs.objectPosition.y.x + cut.v[2] * inputs.objectPosition.y.y + cut.v[3] * inputs.objectPosition.y.z);
  float3 link3;
  Bump(1.0, 1.0, link2, float3(0.0, 0.0, 0.0), 0, inputs, link3);
  NormalOutput(link3, outputs);
}
