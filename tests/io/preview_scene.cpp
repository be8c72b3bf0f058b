// A CPU ray caster for eyeballing scene geometry without a GPU renderer: flat colour per
// material (hashed), Lambert from the scene's lights, emissive materials bright.
// `scenes_preview SCENE OUT.png [WIDTHxHEIGHT] [CAMPATH FRAME]`, SCENE a built-in spec
// (`classroom`, `landscape:terrain=128`) or a glTF/OBJ file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/builtin/builtin_scenes.h"
#include "runtime/scene/builtin/camera_path.h"
#include "tools/io/image_io.h"
#include "tools/io/scene_import.h"

namespace {

using namespace memograph;

struct Triangle {
  glm::vec3 a, e1, e2;
  glm::vec3 normal;
  std::uint32_t material;
};

struct Node {
  glm::vec3 lo, hi;
  int left = -1, right = -1;  // children, or -1 for a leaf
  int first = 0, count = 0;   // leaf triangles
};

struct Bvh {
  std::vector<Triangle> tris;
  std::vector<Node> nodes;

  int build(int first, int count) {
    Node node;
    node.lo = glm::vec3(INFINITY);
    node.hi = glm::vec3(-INFINITY);
    for (int i = first; i < first + count; ++i) {
      const Triangle& t = tris[i];
      for (glm::vec3 p : {t.a, t.a + t.e1, t.a + t.e2}) {
        node.lo = glm::min(node.lo, p);
        node.hi = glm::max(node.hi, p);
      }
    }
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    if (count <= 4) {
      nodes[index].first = first;
      nodes[index].count = count;
      return index;
    }
    const glm::vec3 extent = node.hi - node.lo;
    const int axis =
        extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
    const auto centroid = [axis](const Triangle& t) {
      return t.a[axis] + (t.e1[axis] + t.e2[axis]) / 3;
    };
    std::nth_element(
        tris.begin() + first, tris.begin() + first + count / 2, tris.begin() + first + count,
        [&](const Triangle& x, const Triangle& y) { return centroid(x) < centroid(y); });
    const int left = build(first, count / 2);
    const int right = build(first + count / 2, count - count / 2);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  }

  static bool hitBox(const Node& n, glm::vec3 o, glm::vec3 inv, float tMax) {
    const glm::vec3 t0 = (n.lo - o) * inv, t1 = (n.hi - o) * inv;
    const glm::vec3 mn = glm::min(t0, t1), mx = glm::max(t0, t1);
    const float enter = std::max(std::max(mn.x, mn.y), std::max(mn.z, 0.0f));
    const float exit = std::min(std::min(mx.x, mx.y), std::min(mx.z, tMax));
    return enter <= exit;
  }

  // Closest hit (Möller–Trumbore); returns the triangle index or -1.
  int trace(glm::vec3 o, glm::vec3 d, float& t) const {
    const glm::vec3 inv = 1.0f / d;
    int best = -1;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top) {
      const Node& n = nodes[stack[--top]];
      if (!hitBox(n, o, inv, t))
        continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          const Triangle& tri = tris[i];
          const glm::vec3 p = glm::cross(d, tri.e2);
          const float det = glm::dot(tri.e1, p);
          if (std::abs(det) < 1e-12f)
            continue;
          const glm::vec3 s = o - tri.a;
          const float u = glm::dot(s, p) / det;
          if (u < 0 || u > 1)
            continue;
          const glm::vec3 q = glm::cross(s, tri.e1);
          const float v = glm::dot(d, q) / det;
          if (v < 0 || u + v > 1)
            continue;
          const float h = glm::dot(tri.e2, q) / det;
          if (h > 1e-4f && h < t) {
            t = h;
            best = i;
          }
        }
      } else if (top < 62) {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
    return best;
  }
};

glm::vec3 materialColor(std::uint32_t m) {
  std::uint32_t h = m * 2654435761u + 12345u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return glm::vec3((h & 255) / 255.0f, ((h >> 8) & 255) / 255.0f, ((h >> 16) & 255) / 255.0f) *
             0.7f +
         0.15f;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: scenes_preview SCENE OUT.png [WxH] [CAMPATH FRAME]\n";
    return 2;
  }
  const std::string sceneArg = argv[1];
  int width = 320, height = 180;
  if (argc >= 4)
    std::sscanf(argv[3], "%dx%d", &width, &height);
  compiler::Diagnostics diagnostics;
  runtime::Scene scene;
  if (sceneArg.find('.') != std::string::npos) {
    auto imported = io::importScene(sceneArg, "", diagnostics);
    if (!imported) {
      std::cerr << compiler::formatDiagnostics(diagnostics);
      return 1;
    }
    scene = std::move(*imported);
  } else {
    std::string error;
    const auto spec = runtime::parseBuiltinSceneSpec(sceneArg, error);
    if (!spec) {
      std::cerr << error << '\n';
      return 1;
    }
    scene = runtime::makeBuiltinScene(spec->name, spec->options);
  }
  runtime::Camera camera = scene.camera;
  if (argc >= 6) {
    const auto path = runtime::loadCameraPath(argv[4], diagnostics);
    if (!path) {
      std::cerr << compiler::formatDiagnostics(diagnostics);
      return 1;
    }
    camera = path->frames[std::stoul(argv[5]) % path->frames.size()];
  }
  Bvh bvh;
  for (const runtime::Instance& instance : scene.instances) {
    const runtime::Mesh& mesh = scene.meshes[instance.mesh];
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = glm::vec3(instance.objectToWorld *
                         glm::vec4(mesh.positions[mesh.indices[i + k]], 1.0f));
      }
      const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
      if (glm::length(n) == 0.0f)
        continue;
      bvh.tris.push_back({p[0], p[1] - p[0], p[2] - p[0], glm::normalize(n), instance.material});
    }
  }
  bvh.build(0, static_cast<int>(bvh.tris.size()));
  std::vector<bool> emissive;
  for (const auto& m : scene.materials)
    emissive.push_back(m.graphText.find("EmissionOutput") != std::string::npos);

  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
  const float aspect = static_cast<float>(width) / height;
  runtime::HdrImage image{std::uint32_t(width), std::uint32_t(height),
                          std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float sx = (2.0f * (x + 0.5f) / width - 1.0f) * tanHalf * aspect;
      const float sy = (1.0f - 2.0f * (y + 0.5f) / height) * tanHalf;
      const glm::vec3 d = glm::normalize(forward + sx * right + sy * up);
      float t = 1e30f;
      const int hit = bvh.trace(camera.position, d, t);
      glm::vec3 color = scene.environment.constantRadiance;
      if (hit >= 0) {
        const Triangle& tri = bvh.tris[hit];
        const glm::vec3 p = camera.position + d * t;
        glm::vec3 n = tri.normal;
        if (glm::dot(n, d) > 0)
          n = -n;
        if (emissive[tri.material]) {
          color = glm::vec3(1.0f);
        } else {
          glm::vec3 light = glm::vec3(0.08f) + 0.3f * scene.environment.constantRadiance;
          for (const runtime::Light& l : scene.lights) {
            glm::vec3 toLight;
            float dist = 1e30f;
            glm::vec3 e = l.intensity;
            if (l.type == runtime::LightType::Point) {
              toLight = l.position - p;
              dist = glm::length(toLight);
              toLight /= dist;
              e /= dist * dist;
            } else {
              toLight = -glm::normalize(l.direction);
            }
            const float c = glm::dot(n, toLight);
            if (c <= 0)
              continue;
            float ts = dist - 1e-3f;
            if (bvh.trace(p + n * 1e-3f, toLight, ts) >= 0)
              continue;  // shadowed
            light += e * c / 3.14159265f;
          }
          color = materialColor(tri.material) * light;
        }
      }
      float* px = image.pixel(x, y);
      px[0] = color.r;
      px[1] = color.g;
      px[2] = color.b;
      px[3] = 1.0f;
    }
  }
  if (!io::writeImage(argv[2], image, {0.0f, io::Tonemap::Aces}, diagnostics)) {
    std::cerr << compiler::formatDiagnostics(diagnostics);
    return 1;
  }
  std::cout << "wrote " << argv[2] << " (" << bvh.tris.size() << " triangles)\n";
  return 0;
}
