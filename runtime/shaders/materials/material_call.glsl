// What the raygen shader and a material's callable shader exchange through
// executeCallableEXT (callable material dispatch): the hit's inputs in, the graph's outputs
// back. Needs the prelude's MaterialInputs and MaterialOutputs first.
#ifndef MG_MATERIAL_CALL_GLSL
#define MG_MATERIAL_CALL_GLSL
struct MaterialCall {
  MaterialInputs inputs;
  MaterialOutputs outputs;
};
// Location of the raygen's callableDataEXT; callable locations are their own namespace,
// apart from the ray payloads' 0 and 1.
const int kMaterialCallLocation = 0;
#endif
