// The environment: a constant radiance, or an equirectangular image (Scene::Environment's
// convention: rows from the zenith down, u = 0.5 looking down -z, u = 0.75 along +x).
#include <gtest/gtest.h>

#include "render_test_support.h"

namespace memograph::runtime {
namespace {

TEST(Environment, ImageIsLookedUpInTheDocumentedDirections) {
  Scene scene;
  // Something to trace against, out of view below the camera.
  scene.meshes.push_back(testing::quad(1.0f));
  scene.materials.push_back({"Grey", "", testing::constantGraph("Grey", {0.5f, 0.5f, 0.5f}, 0.5f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.instances[0].objectToWorld[3] = glm::vec4(0, -100, 0, 1);
  // 4 x 3 texels, each with its own value: red = column, green = row.
  scene.environment.imageWidth = 4;
  scene.environment.imageHeight = 3;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      scene.environment.imageRgb.push_back(float(x));
      scene.environment.imageRgb.push_back(float(y));
      scene.environment.imageRgb.push_back(1.0f);
    }
  Renderer renderer(testing::testOptions());
  RenderSettings settings;
  settings.width = settings.height = 5;
  settings.raysPerPath = 1;
  settings.sharedPrimaryRay = true;
  struct View {
    glm::vec3 target, up;
    float column, row;
  };
  for (const View& view : {View{{0, 0, -1}, {0, 1, 0}, 2, 1}, View{{1, 0, 0}, {0, 1, 0}, 3, 1},
                           View{{0, 1, -0.3f}, {0, 0, -1}, 2, 0}}) {
    scene.camera.position = {0, 0, 0};
    scene.camera.target = view.target;
    scene.camera.up = view.up;
    scene.camera.verticalFovDegrees = 10.0f;
    RenderResult result = renderer.render(scene, settings);
    const float* centre = result.image.pixel(2, 2);
    EXPECT_EQ(centre[0], view.column)
        << "looking at " << view.target.x << "," << view.target.y << "," << view.target.z;
    EXPECT_EQ(centre[1], view.row);
  }
  scene.environment.imageRgb.pop_back();
  EXPECT_THROW(renderer.render(scene, settings), std::invalid_argument);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime

namespace memograph::runtime {
namespace {

// Progressive accumulation averages the frames of a still camera and restarts when the
// camera moves, so a camera path's image shows only its last camera's frames.
TEST(Accumulation, RestartsWhenTheCameraMoves) {
  Scene scene;
  scene.meshes.push_back(testing::quad(1.0f));
  scene.materials.push_back({"Grey", "", testing::constantGraph("Grey", {0.5f, 0.5f, 0.5f}, 0.5f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.instances[0].objectToWorld[3] = glm::vec4(0, -100, 0, 1);
  // Sky: red towards -z (u = 0.5), blue towards +z (u = 0 / 1).
  scene.environment.imageWidth = 3;
  scene.environment.imageHeight = 1;
  scene.environment.imageRgb = {0, 0, 1, 1, 0, 0, 0, 0, 1};
  Camera towardsRed;
  towardsRed.position = {0, 0, 0};
  towardsRed.target = {0, 0, -1};
  towardsRed.verticalFovDegrees = 5.0f;
  Camera towardsBlue = towardsRed;
  towardsBlue.target = {0, 0, 1};
  Renderer renderer(testing::testOptions());
  RenderSettings settings;
  settings.width = settings.height = 3;
  settings.raysPerPath = 1;
  settings.frames = 3;
  settings.cameraPath = {towardsRed, towardsRed, towardsBlue};
  RenderResult moved = renderer.render(scene, settings);
  EXPECT_EQ(moved.image.pixel(1, 1)[0], 0.0f);
  EXPECT_EQ(moved.image.pixel(1, 1)[2], 1.0f);
  settings.cameraPath = {towardsRed};  // the last camera repeats: a still camera
  RenderResult still = renderer.render(scene, settings);
  EXPECT_EQ(still.image.pixel(1, 1)[0], 1.0f);
  ASSERT_EQ(still.stats.frames.size(), 3u);
  EXPECT_TRUE(renderer.context().validationErrors().empty());
}

}  // namespace
}  // namespace memograph::runtime
