#include "tools/io/scene_import.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scenes/material_recipes.h"
#include "runtime/scenes/mesh_builder.h"
#include "runtime/scenes/scene_validation.h"

namespace memograph::io {
namespace {

namespace fs = std::filesystem;
using runtime::Scene;

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // assimp matrices are row-major, glm's column-major.
  return glm::transpose(glm::mat4(m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3,
                                  m.c4, m.d1, m.d2, m.d3, m.d4));
}
glm::vec3 toGlm(const aiVector3D& v) {
  return {v.x, v.y, v.z};
}

// Warnings without a source position: the import is about a whole file.
void warn(compiler::Diagnostics& diagnostics, const std::string& path, std::string message) {
  diagnostics.warning(compiler::SourceFile{path, {}}, {}, std::move(message));
}

runtime::Mesh convertMesh(const aiMesh& in, const std::string& path,
                          compiler::Diagnostics& diagnostics) {
  runtime::Mesh mesh;
  mesh.name = in.mName.C_Str();
  mesh.positions.reserve(in.mNumVertices);
  for (unsigned v = 0; v < in.mNumVertices; ++v)
    mesh.positions.push_back(toGlm(in.mVertices[v]));
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3)
      continue;  // points and lines (sorted out by SortByPType)
    for (unsigned k = 0; k < 3; ++k)
      mesh.indices.push_back(face.mIndices[k]);
  }
  // GenSmoothNormals guarantees normals; guard against zero ones in degenerate input.
  for (unsigned v = 0; v < in.mNumVertices; ++v) {
    glm::vec3 n = in.mNormals ? toGlm(in.mNormals[v]) : glm::vec3(0.0f);
    mesh.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0));
  }
  if (in.HasTextureCoords(0)) {
    if (in.mNumUVComponents[0] < 2) {
      warn(diagnostics, path, "mesh '" + mesh.name + "' has 1-D texture coordinates; v set to 0");
    }
    for (unsigned v = 0; v < in.mNumVertices; ++v) {
      // assimp flips nothing here (no aiProcess_FlipUVs): glTF's v points down the image,
      // which is what the renderer's textureGrad expects with top-row-first images.
      mesh.uvs.push_back({in.mTextureCoords[0][v].x,
                          in.mNumUVComponents[0] >= 2 ? in.mTextureCoords[0][v].y : 0.0f});
    }
  } else {
    warn(diagnostics, path,
         "mesh '" + mesh.name + "' has no texture coordinates: its materials see uv = 0");
  }
  if (!mesh.uvs.empty() && in.mTangents && in.mBitangents) {
    for (unsigned v = 0; v < in.mNumVertices; ++v) {
      const glm::vec3 n = mesh.normals[v];
      glm::vec3 t = toGlm(in.mTangents[v]);
      t -= n * glm::dot(n, t);
      if (glm::length(t) < 1e-8f || !std::isfinite(t.x)) {
        t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                 : glm::cross(n, glm::vec3(0, 1, 0));
      }
      t = glm::normalize(t);
      const float w = glm::dot(glm::cross(n, t), toGlm(in.mBitangents[v])) < 0.0f ? -1.0f : 1.0f;
      mesh.tangents.emplace_back(t, w);
    }
  } else if (!mesh.uvs.empty()) {
    runtime::computeTangents(mesh);
  }
  if (in.HasVertexColors(0)) {
    for (unsigned v = 0; v < in.mNumVertices; ++v) {
      const aiColor4D& c = in.mColors[0][v];
      mesh.colors.push_back({c.r, c.g, c.b, c.a});
    }
  }
  return mesh;
}

std::string fileSafe(std::string name) {
  for (char& c : name) {
    if (c == '/' || c == '\\' || c == ':')
      c = '_';
  }
  return name;
}

struct Importer {
  const aiScene& in;
  std::string path;
  std::string materialsDir;
  compiler::Diagnostics& diagnostics;
  Scene scene;
  std::vector<std::uint32_t> meshMaterial;       // assimp mesh → scene material
  std::vector<int> meshIndex;                    // assimp mesh → scene mesh (-1: skipped)
  std::map<std::string, glm::mat4> nodeWorld;    // node name → world transform
  std::map<unsigned, std::uint32_t> materialOf;  // assimp material → scene material
  int missingMaterial = -1;

  std::uint32_t material(unsigned assimpIndex) {
    if (auto it = materialOf.find(assimpIndex); it != materialOf.end())
      return it->second;
    const aiMaterial* m = in.mMaterials[assimpIndex];
    std::string name = m->GetName().C_Str();
    if (name.empty())
      name = "material" + std::to_string(assimpIndex);
    std::uint32_t index = 0;
    const fs::path graph = fs::path(materialsDir) / (fileSafe(name) + ".mgraph");
    if (!materialsDir.empty() && fs::is_regular_file(graph)) {
      scene.materials.push_back(runtime::MaterialRef{name, graph.string(), {}});
      index = static_cast<std::uint32_t>(scene.materials.size() - 1);
    } else {
      warn(diagnostics, path,
           "material '" + name + "' has no graph (" +
               (materialsDir.empty() ? std::string("no materials folder was given")
                                     : "looked for " + graph.string()) +
               "); it renders as the magenta checker");
      if (missingMaterial < 0) {
        scene.materials.push_back(runtime::MaterialRef{
            kMissingMaterialName, {}, runtime::missingMaterialGraph(kMissingMaterialName)});
        missingMaterial = static_cast<int>(scene.materials.size() - 1);
      }
      index = static_cast<std::uint32_t>(missingMaterial);
    }
    materialOf.emplace(assimpIndex, index);
    return index;
  }

  void visit(const aiNode& node, const glm::mat4& parent) {
    const glm::mat4 world = parent * toGlm(node.mTransformation);
    nodeWorld.emplace(node.mName.C_Str(), world);
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const unsigned m = node.mMeshes[i];
      if (meshIndex[m] < 0)
        continue;
      scene.instances.push_back(
          runtime::Instance{static_cast<std::uint32_t>(meshIndex[m]), meshMaterial[m], world});
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
      visit(*node.mChildren[c], world);
  }

  bool isGltf() const {
    std::string ext = fs::path(path).extension().string();
    for (char& ch : ext)
      ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext == ".gltf" || ext == ".glb";
  }

  glm::mat4 worldOf(const aiString& name) {
    const auto it = nodeWorld.find(name.C_Str());
    return it == nodeWorld.end() ? glm::mat4(1.0f) : it->second;
  }

  void convertLights() {
    for (unsigned i = 0; i < in.mNumLights; ++i) {
      const aiLight& l = *in.mLights[i];
      const glm::mat4 world = worldOf(l.mName);
      runtime::Light light;
      // assimp folds glTF's intensity into the colour; the renderer takes it as W/sr (point)
      // or W/m² (directional) without photometric conversion.
      light.intensity = {l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b};
      switch (l.mType) {
        case aiLightSource_SPOT:
          warn(diagnostics, path,
               "light '" + std::string(l.mName.C_Str()) +
                   "' is a spot light: imported as a point light");
          [[fallthrough]];
        case aiLightSource_POINT:
          light.type = runtime::LightType::Point;
          light.position = glm::vec3(world * glm::vec4(toGlm(l.mPosition), 1.0f));
          break;
        case aiLightSource_DIRECTIONAL: {
          light.type = runtime::LightType::Directional;
          const glm::vec3 d = glm::vec3(world * glm::vec4(toGlm(l.mDirection), 0.0f));
          light.direction = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, -1, 0);
          break;
        }
        default:
          warn(diagnostics, path,
               "light '" + std::string(l.mName.C_Str()) + "' has an unsupported type; skipped");
          continue;
      }
      scene.lights.push_back(light);
    }
  }

  void convertCamera() {
    if (in.mNumCameras == 0) {
      frameBounds();
      return;
    }
    if (in.mNumCameras > 1) {
      warn(diagnostics, path,
           "the file has " + std::to_string(in.mNumCameras) + " cameras; using the first, '" +
               std::string(in.mCameras[0]->mName.C_Str()) + "'");
    }
    const aiCamera& c = *in.mCameras[0];
    const glm::mat4 world = worldOf(c.mName);
    runtime::Camera& camera = scene.camera;
    // assimp 5.2's glTF reader copies the node's translation into mPosition although the
    // node transform holds it too; a glTF camera sits at its node's origin by definition.
    const glm::vec3 local = isGltf() ? glm::vec3(0.0f) : toGlm(c.mPosition);
    camera.position = glm::vec3(world * glm::vec4(local, 1.0f));
    const glm::vec3 look = glm::vec3(world * glm::vec4(toGlm(c.mLookAt), 0.0f));
    camera.target =
        camera.position + (glm::length(look) > 0 ? glm::normalize(look) : glm::vec3(0, 0, -1));
    const glm::vec3 up = glm::vec3(world * glm::vec4(toGlm(c.mUp), 0.0f));
    camera.up = glm::length(up) > 0 ? glm::normalize(up) : glm::vec3(0, 1, 0);
    const float aspect = c.mAspect > 0.0f ? c.mAspect : 1.0f;
    if (isGltf()) {
      // assimp 5.2's glTF reader stores yfov · aspectRatio (measured in the import test).
      camera.verticalFovDegrees = glm::degrees(c.mHorizontalFOV / aspect);
    } else {
      // assimp's documented meaning: half the horizontal angle.
      camera.verticalFovDegrees =
          glm::degrees(2.0f * std::atan(std::tan(c.mHorizontalFOV) / aspect));
    }
  }

  // No camera in the file: look at the bounds' centre from the +z side, far enough back to
  // see all of it at the default 45° field of view.
  void frameBounds() {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const runtime::Instance& i : scene.instances) {
      for (const glm::vec3& p : scene.meshes[i.mesh].positions) {
        const glm::vec3 w = glm::vec3(i.objectToWorld * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    scene.camera.target = centre;
    scene.camera.position = centre + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) *
                                         (radius / std::sin(glm::radians(22.5f)));
  }
};

}  // namespace

std::optional<Scene> importScene(const std::string& path, const std::string& materialsDir,
                                 compiler::Diagnostics& diagnostics) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    diagnostics.error(path, "no such scene file");
    return std::nullopt;
  }
  if (!fs::is_regular_file(path, ec)) {
    diagnostics.error(path, "not a regular file");
    return std::nullopt;
  }
  if (!materialsDir.empty() && !fs::is_directory(materialsDir, ec)) {
    diagnostics.error(materialsDir, "the materials folder does not exist");
    return std::nullopt;
  }
  Assimp::Importer importer;
  // Points and lines are removed; everything else becomes indexed triangles with normals,
  // and tangents wherever there are UVs.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* in = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_CalcTangentSpace | aiProcess_SortByPType |
                aiProcess_ValidateDataStructure | aiProcess_FindInvalidData);
  if (!in) {
    diagnostics.error(path, std::string("cannot import the scene: ") + importer.GetErrorString());
    return std::nullopt;
  }
  if ((in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !in->mRootNode) {
    diagnostics.error(path, "the scene is incomplete (no node hierarchy or no meshes)");
    return std::nullopt;
  }
  Importer imp{*in, path, materialsDir, diagnostics, {}, {}, {}, {}, {}};
  imp.meshIndex.assign(in->mNumMeshes, -1);
  imp.meshMaterial.assign(in->mNumMeshes, 0);
  for (unsigned m = 0; m < in->mNumMeshes; ++m) {
    const aiMesh& mesh = *in->mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || mesh.mNumFaces == 0)
      continue;
    imp.scene.meshes.push_back(convertMesh(mesh, path, diagnostics));
    imp.meshIndex[m] = static_cast<int>(imp.scene.meshes.size() - 1);
    imp.meshMaterial[m] = imp.material(mesh.mMaterialIndex);
  }
  if (imp.scene.meshes.empty()) {
    diagnostics.error(path, "the scene has no triangle meshes");
    return std::nullopt;
  }
  imp.visit(*in->mRootNode, glm::mat4(1.0f));
  if (imp.scene.instances.empty()) {
    diagnostics.error(path, "no node of the scene places a mesh");
    return std::nullopt;
  }
  imp.convertLights();
  imp.convertCamera();
  // assimp validated its own structure; this checks what the renderer relies on.
  if (!runtime::validateScene(imp.scene, path, diagnostics))
    return std::nullopt;
  return std::move(imp.scene);
}

}  // namespace memograph::io
