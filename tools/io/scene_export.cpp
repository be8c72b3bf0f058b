#include "tools/io/scene_export.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/host/atomic_file.h"
#include "tools/io/base64.h"

namespace memograph::io {
namespace {

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  return buffer;
}

std::string array(const float* values, int count) {
  std::string out = "[";
  for (int i = 0; i < count; ++i) {
    if (i)
      out += ", ";
    out += number(values[i]);
  }
  out += ']';
  return out;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  out += '"';
  return out;
}

// Accumulates the buffer, its views and accessors.
struct Buffers {
  std::vector<unsigned char> bytes;
  std::vector<std::string> views, accessors;

  // Appends `count` elements of `components` floats (or uint32 when `indices`); returns
  // the accessor index.
  int add(const void* data, std::size_t count, int components, const char* type, bool indices,
          const std::string& extra = {}) {
    while (bytes.size() % 4)
      bytes.push_back(0);
    const std::size_t offset = bytes.size(), length = count * components * 4;
    bytes.resize(offset + length);
    std::memcpy(bytes.data() + offset, data, length);
    views.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) +
                    ", \"byteLength\": " + std::to_string(length) +
                    (indices ? ", \"target\": 34963}" : ", \"target\": 34962}"));
    accessors.push_back("{\"bufferView\": " + std::to_string(views.size() - 1) +
                        ", \"componentType\": " + (indices ? "5125" : "5126") + ", \"count\": " +
                        std::to_string(count) + ", \"type\": \"" + type + "\"" + extra + "}");
    return static_cast<int>(accessors.size() - 1);
  }
};

// A node matrix whose -z axis looks from `eye` along `forward` (cameras, directional lights).
glm::mat4 lookAlong(glm::vec3 eye, glm::vec3 forward) {
  forward = glm::normalize(forward);
  const glm::vec3 up =
      std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::inverse(glm::lookAt(eye, eye + forward, up));
}

}  // namespace

bool exportSceneGltf(const runtime::Scene& scene, const std::string& path,
                     compiler::Diagnostics& diagnostics) {
  Buffers buffers;
  // Attribute objects per scene mesh (shared by every glTF mesh made from it).
  std::vector<std::string> attributes;
  std::vector<int> indexAccessor;
  for (const runtime::Mesh& mesh : scene.meshes) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const std::string bounds = ", \"min\": " + array(&lo.x, 3) + ", \"max\": " + array(&hi.x, 3);
    std::string a =
        "{\"POSITION\": " + std::to_string(buffers.add(mesh.positions.data(), mesh.positions.size(),
                                                       3, "VEC3", false, bounds));
    a += ", \"NORMAL\": " +
         std::to_string(buffers.add(mesh.normals.data(), mesh.normals.size(), 3, "VEC3", false));
    if (!mesh.uvs.empty()) {
      a += ", \"TEXCOORD_0\": " +
           std::to_string(buffers.add(mesh.uvs.data(), mesh.uvs.size(), 2, "VEC2", false));
    }
    if (!mesh.tangents.empty()) {
      a += ", \"TANGENT\": " + std::to_string(buffers.add(mesh.tangents.data(),
                                                          mesh.tangents.size(), 4, "VEC4", false));
    }
    if (!mesh.colors.empty()) {
      a += ", \"COLOR_0\": " +
           std::to_string(buffers.add(mesh.colors.data(), mesh.colors.size(), 4, "VEC4", false));
    }
    a += '}';
    attributes.push_back(a);
    indexAccessor.push_back(
        buffers.add(mesh.indices.data(), mesh.indices.size(), 1, "SCALAR", true));
  }

  std::vector<std::string> meshes, nodes;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> meshOf;  // (mesh, material) → glTF
  for (const runtime::Instance& instance : scene.instances) {
    const auto key = std::make_pair(instance.mesh, instance.material);
    auto it = meshOf.find(key);
    if (it == meshOf.end()) {
      meshes.push_back("{\"name\": " + quoted(scene.meshes[instance.mesh].name) +
                       ", \"primitives\": [{\"attributes\": " + attributes[instance.mesh] +
                       ", \"indices\": " + std::to_string(indexAccessor[instance.mesh]) +
                       ", \"material\": " + std::to_string(instance.material) + "}]}");
      it = meshOf.emplace(key, static_cast<int>(meshes.size() - 1)).first;
    }
    nodes.push_back("{\"mesh\": " + std::to_string(it->second) +
                    ", \"matrix\": " + array(&instance.objectToWorld[0][0], 16) + "}");
  }
  const runtime::Camera& camera = scene.camera;
  const glm::mat4 cameraMatrix = lookAlong(camera.position, camera.target - camera.position);
  nodes.push_back(
      "{\"name\": \"Camera\", \"camera\": 0, \"matrix\": " + array(&cameraMatrix[0][0], 16) + "}");
  std::vector<std::string> lights;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const runtime::Light& light = scene.lights[i];
    const float scale = std::max({light.intensity.r, light.intensity.g, light.intensity.b, 1e-20f});
    const glm::vec3 color = light.intensity / scale;
    const bool point = light.type == runtime::LightType::Point;
    lights.push_back(std::string("{\"type\": ") + (point ? "\"point\"" : "\"directional\"") +
                     ", \"color\": " + array(&color.x, 3) + ", \"intensity\": " + number(scale) +
                     "}");
    const glm::mat4 m = point ? glm::translate(glm::mat4(1.0f), light.position)
                              : lookAlong(glm::vec3(0.0f), light.direction);
    nodes.push_back(
        "{\"name\": \"Light" + std::to_string(i) + "\", \"matrix\": " + array(&m[0][0], 16) +
        ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": " + std::to_string(i) + "}}}");
  }

  const auto join = [](const std::vector<std::string>& items, const char* indent) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
      out += indent + items[i] + (i + 1 < items.size() ? ",\n" : "\n");
    }
    return out;
  };
  std::vector<std::string> materials, sceneNodes;
  for (const runtime::MaterialRef& m : scene.materials)
    materials.push_back("{\"name\": " + quoted(m.name) + "}");
  for (std::size_t i = 0; i < nodes.size(); ++i)
    sceneNodes.push_back(std::to_string(i));
  std::string sceneNodeList;
  for (std::size_t i = 0; i < sceneNodes.size(); ++i)
    sceneNodeList += (i ? ", " : "") + sceneNodes[i];

  std::string json = "{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"memograph\"},\n";
  if (!lights.empty()) {
    json += "  \"extensionsUsed\": [\"KHR_lights_punctual\"],\n";
    json += "  \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [\n" + join(lights, "    ") +
            "  ]}},\n";
  }
  json += "  \"scene\": 0,\n  \"scenes\": [{\"nodes\": [" + sceneNodeList +
          "], \"extras\": {\"memographEnvironment\": " +
          array(&scene.environment.constantRadiance.x, 3) + "}}],\n";
  json += "  \"nodes\": [\n" + join(nodes, "    ") + "  ],\n";
  json += "  \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": " +
          number(glm::radians(camera.verticalFovDegrees)) +
          ", \"aspectRatio\": 1.77777778, \"znear\": 0.01}}],\n";
  json += "  \"materials\": [\n" + join(materials, "    ") + "  ],\n";
  json += "  \"meshes\": [\n" + join(meshes, "    ") + "  ],\n";
  json += "  \"accessors\": [\n" + join(buffers.accessors, "    ") + "  ],\n";
  json += "  \"bufferViews\": [\n" + join(buffers.views, "    ") + "  ],\n";
  json += "  \"buffers\": [{\"byteLength\": " + std::to_string(buffers.bytes.size()) +
          ", \"uri\": \"data:application/octet-stream;base64," + base64Encode(buffers.bytes) +
          "\"}]\n}\n";

  std::string error;
  if (!files::writeFileAtomically(path, json, error)) {
    diagnostics.error(path, error);
    return false;
  }
  return true;
}

}  // namespace memograph::io
