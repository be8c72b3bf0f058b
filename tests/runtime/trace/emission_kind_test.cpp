// Emissive NEE takes a material's declared constant emission only where its compiled graph
// bears it out (emissionKindsVerified, runtime/scene/scene_upload.h): a Constant graph reads no
// input and no texture; a ConstantFront one (an area lamp's quad) may read backfacing. A
// declaration the graph contradicts falls back to evaluating the graph at light samples.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/materials/material_linker.h"
#include "runtime/scene/scene_upload.h"

namespace memograph::runtime {
namespace {

using Kind = MaterialRef::EmissionKind;

MaterialRef emitter(const std::string& name, const std::string& body, Kind kind) {
  MaterialRef m;
  m.name = name;
  m.graphText = "material " + name + ";\n" + body;
  m.emissionEstimate = glm::vec3(2.0f);
  m.emissionKind = kind;
  return m;
}

const char* kConstant = "EmissionOutput Color=(2, 2, 2) Strength=1;\n";
const char* kByPosition =
    "PositionInput Out>0;\nSeparateXYZ Vector<0 X>1;\nEmissionOutput Color=(2, 2, 2) Strength<1;\n";
const char* kFrontOnly =
    "BackfacingInput Out>0;\n"
    "Math Value=1 Value1<0 Value2=0 Operation=1 UseClamp=0 Result>1;\n"
    "EmissionOutput Color=(2, 2, 2) Strength<1;\n";

TEST(EmissionKinds, DeclaredConstantsHoldOnlyForGraphsThatCannotVary) {
  Scene scene;
  scene.materials = {emitter("Lamp", kConstant, Kind::Constant),
                     emitter("Gradient", kByPosition, Kind::Constant),
                     emitter("AreaQuad", kFrontOnly, Kind::ConstantFront),
                     emitter("AreaQuadClaimedTwoSided", kFrontOnly, Kind::Constant),
                     emitter("GradientClaimedFront", kByPosition, Kind::ConstantFront),
                     emitter("Evaluated", kConstant, Kind::Graph)};
  const LinkedMaterials linked = linkMaterials(scene.materials, MaterialLinkOptions{});
  EXPECT_EQ(emissionKindsVerified(scene, linked),
            (std::vector<Kind>{Kind::Constant, Kind::Graph, Kind::ConstantFront, Kind::Graph,
                               Kind::Graph, Kind::Graph}));
}

}  // namespace
}  // namespace memograph::runtime
