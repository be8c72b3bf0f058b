// Bad scenes, missing files and unsupported requests end in exceptions whose messages name
// the problem and the place, never in a crash or a device fault.
#include <stdexcept>

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "runtime/host/image.h"

namespace memograph::runtime {
namespace {

Scene oneQuad() {
  return testing::greyQuadScene();
}

RenderSettings tiny() {
  RenderSettings settings;
  settings.width = settings.height = 8;
  return settings;
}

// Runs `render` and returns the message of the exception it must throw.
template <typename Exception>
std::string messageOf(Renderer& renderer, const Scene& scene, const RenderSettings& settings) {
  try {
    renderer.render(scene, settings);
  } catch (const Exception& e) {
    return e.what();
  }
  ADD_FAILURE() << "render did not throw";
  return {};
}

class BadInput : public ::testing::Test {
 protected:
  Renderer renderer{testing::testOptions()};
};

TEST_F(BadInput, MissingGraphFileIsNamed) {
  Scene scene = oneQuad();
  scene.materials[0] = {"Wood", "/nonexistent/wood.mgraph", ""};
  std::string message = messageOf<std::runtime_error>(renderer, scene, tiny());
  EXPECT_NE(message.find("/nonexistent/wood.mgraph"), std::string::npos) << message;
  EXPECT_NE(message.find("Wood"), std::string::npos) << message;
}

TEST_F(BadInput, GraphSyntaxErrorCarriesFileLineAndColumn) {
  Scene scene = oneQuad();
  scene.materials[0] = {"Broken", "", "material Broken;\nBaseColorOutput Color=(1, 1, 1)\n"};
  std::string message = messageOf<std::runtime_error>(renderer, scene, tiny());
  EXPECT_NE(message.find("<Broken>:"), std::string::npos) << message;
  EXPECT_NE(message.find("error"), std::string::npos) << message;
}

TEST_F(BadInput, UnknownNodeIsReported) {
  Scene scene = oneQuad();
  scene.materials[0] = {"Odd", "", "material Odd;\nNoSuchNode Out>0;\nBaseColorOutput Color<0;\n"};
  std::string message = messageOf<std::runtime_error>(renderer, scene, tiny());
  EXPECT_NE(message.find("NoSuchNode"), std::string::npos) << message;
}

TEST_F(BadInput, OutOfRangeReferencesAreNamed) {
  Scene scene = oneQuad();
  scene.instances[0].material = 3;
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, scene, tiny()).find("material 3"),
            std::string::npos);
  scene = oneQuad();
  scene.instances[0].mesh = 9;
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, scene, tiny()).find("mesh 9"),
            std::string::npos);
  scene = oneQuad();
  scene.meshes[0].indices.push_back(77);
  scene.meshes[0].indices.push_back(0);
  scene.meshes[0].indices.push_back(1);
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, scene, tiny()).find("is 77"),
            std::string::npos);
}

TEST_F(BadInput, EmptySceneAndBadSettingsAreRejected) {
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, Scene{}, tiny()).find("no meshes"),
            std::string::npos);
  RenderSettings settings = tiny();
  settings.width = 0;
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, oneQuad(), settings).find("image size"),
            std::string::npos);
  // The largest image the settings allow is one 4 GiB buffer of 4 floats a pixel: more than
  // any device here binds (lavapipe: 128 MiB storage-buffer range; the H200: 4094 MiB per
  // allocation). Refused before anything compiles, naming the image.
  settings = tiny();
  settings.width = settings.height = 16384;
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, oneQuad(), settings)
                .find("16384x16384 image (16 bytes a pixel) needs 4294967296 bytes"),
            std::string::npos);
  Scene scene = oneQuad();
  scene.camera.target = scene.camera.position;
  EXPECT_NE(messageOf<std::invalid_argument>(renderer, scene, tiny()).find("camera"),
            std::string::npos);
}

TEST_F(BadInput, MissingTextureIsNamed) {
  Scene scene = oneQuad();
  scene.materials[0] = {"Tex", "",
                        "material Tex;\nUVInput UV>0;\nImageTexture Image=\"missing.pfm\" UV<0 "
                        "Color>1;\nBaseColorOutput Color<1;\n"};
  std::string message = messageOf<std::runtime_error>(renderer, scene, tiny());
  EXPECT_NE(message.find("missing.pfm"), std::string::npos) << message;
}

TEST(BadOptions, UnknownBackendAndDeviceIndexAreExplained) {
  EXPECT_THROW(parseBackend("optix"), std::invalid_argument);
  RendererOptions options = testing::testOptions();
  options.context.deviceIndex = 99;
  // The device opens on the renderer's own thread: its error comes from context() and from
  // render(), each time they are called.
  Renderer renderer(options);
  for (int call = 0; call < 2; ++call) {
    try {
      renderer.context();
      ADD_FAILURE() << "device 99 was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    }
  }
  try {
    renderer.render(oneQuad(), tiny());
    ADD_FAILURE() << "device 99 rendered";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

TEST(BadFiles, PfmReaderRejectsOtherFiles) {
  EXPECT_THROW(readPfm("/nonexistent.pfm"), std::runtime_error);
  EXPECT_THROW(loadTextureCore("/nonexistent/wood.png"), std::runtime_error);
}

}  // namespace
}  // namespace memograph::runtime
