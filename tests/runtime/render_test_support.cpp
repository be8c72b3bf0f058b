#include "render_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

namespace memograph::runtime::testing {

RendererOptions testOptions(Backend backend) {
  if (!std::getenv("XDG_RUNTIME_DIR")) {
    auto dir = std::filesystem::temp_directory_path() / "memograph-xdg-runtime";
    std::filesystem::create_directories(dir);
    setenv("XDG_RUNTIME_DIR", dir.c_str(), 0);
  }
  RendererOptions options;
  options.context.backend = backend;
  options.context.validation = validationLayerAvailable();
  options.shaderCacheDirectory =
      std::filesystem::temp_directory_path() / "memograph-test-shader-cache";
  options.nodeLibraryDirectory = MEMOGRAPH_TEST_NODES_DIR;
  return options;
}

Mesh quad(float size, float uvScale) {
  Mesh mesh;
  mesh.name = "quad";
  float h = size * 0.5f;
  mesh.positions = {{-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}};
  mesh.normals.assign(4, glm::vec3(0, 1, 0));
  mesh.uvs = {{0, 0}, {uvScale, 0}, {uvScale, uvScale}, {0, uvScale}};
  mesh.indices = {0, 2, 1, 0, 3, 2};
  return mesh;
}

Mesh sphere(int segments) {
  Mesh mesh;
  mesh.name = "sphere";
  int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    float v = float(r) / float(rings);
    float theta = v * 3.14159265f;
    for (int s = 0; s <= segments; ++s) {
      float u = float(s) / float(segments);
      float phi = u * 2.0f * 3.14159265f;
      glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                  std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(p);
      mesh.normals.push_back(p);
      mesh.uvs.push_back({u, v});
    }
  }
  int stride = segments + 1;
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      std::uint32_t a = r * stride + s, b = a + 1, c = a + stride, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  }
  return mesh;
}

Mesh unitCube() {
  Mesh mesh;
  mesh.name = "cube";
  const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    // Two axes spanning the face, u x v = n, so the quad winds counter-clockwise seen from n.
    const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(0, 0, n.y) : glm::vec3(-n.z, 0, n.x);
    const glm::vec3 v = glm::cross(n, u);
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    for (const glm::vec2 c :
         {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      mesh.positions.push_back(0.5f * (n + c.x * u + c.y * v));
      mesh.normals.push_back(n);
    }
    mesh.indices.insert(mesh.indices.end(),
                        {first, first + 1, first + 2, first, first + 2, first + 3});
  }
  return mesh;
}

std::string constantGraph(const std::string& name, glm::vec3 c, float roughness) {
  std::ostringstream text;
  text << "material " << name << ";\n"
       << "BaseColorOutput Color=(" << c.x << ", " << c.y << ", " << c.z << ");\n"
       << "RoughnessOutput Roughness=" << roughness << ";\n";
  return text.str();
}

TextureImage flatTexture(glm::vec3 color) {
  TextureImage texture;
  for (std::uint32_t size : {4u, 2u, 1u}) {
    HdrImage image;
    image.width = image.height = size;
    for (std::uint32_t i = 0; i < size * size; ++i)
      image.rgba.insert(image.rgba.end(), {color.x, color.y, color.z, 1.0f});
    texture.levels.push_back(std::move(image));
  }
  return texture;
}

RoundingDifference roundingDifference(const HdrImage& image, const HdrImage& reference) {
  RoundingDifference d;
  EXPECT_EQ(image.rgba.size(), reference.rgba.size());
  if (image.rgba.size() != reference.rgba.size() || reference.rgba.empty())
    return d;
  // The mean over the colour channels only: alpha is 1 wherever a path ran, so a mean with it
  // would pass a "not black" check on a black image.
  for (std::size_t i = 0; i < reference.rgba.size(); ++i) {
    d.largest = std::max(d.largest, std::abs(double(image.rgba[i]) - double(reference.rgba[i])));
    if (i % 4 != 3)
      d.referenceMean += std::abs(double(reference.rgba[i]));
  }
  d.referenceMean /= 0.75 * double(reference.rgba.size());
  return d;
}

Scene greyQuadScene(const std::string& material) {
  Scene scene;
  scene.meshes.push_back(quad(2.0f));
  scene.materials.push_back({material, "", constantGraph(material, {0.5f, 0.5f, 0.5f}, 0.5f)});
  scene.instances.push_back({0, 0, glm::mat4(1.0f)});
  scene.camera.position = {0, 3, 1};
  return scene;
}

double meanChannel(const HdrImage& image, int c, int x0, int y0, int x1, int y1) {
  double sum = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++n)
      sum += image.pixel(x, y)[c];
  return n ? sum / n : 0.0;
}

TextureImage levelTaggedChecker(std::uint32_t size, int levels, std::uint32_t period) {
  TextureImage texture;
  for (int level = 0; level < levels; ++level) {
    HdrImage image;
    image.width = image.height = std::max(1u, size >> level);
    image.rgba.resize(std::size_t(image.width) * image.height * 4);
    for (std::uint32_t y = 0; y < image.height; ++y)
      for (std::uint32_t x = 0; x < image.width; ++x) {
        float* p = image.pixel(x, y);
        p[0] = levels > 1 ? float(level) / float(levels - 1) : 0.0f;
        p[1] = float((x / period + y / period) % 2);
        p[2] = 0.0f;
        p[3] = 1.0f;
      }
    texture.levels.push_back(std::move(image));
  }
  return texture;
}

}  // namespace memograph::runtime::testing
