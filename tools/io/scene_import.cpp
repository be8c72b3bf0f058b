#include "tools/io/scene_import.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "compiler/input_file.h"
#include "runtime/scene/builtin/material_recipes.h"
#include "runtime/scene/builtin/mesh_builder.h"
#include "runtime/scene/builtin/scene_validation.h"
#include "tools/io/gltf_precheck.h"
#include "tools/io/obj_precheck.h"

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

// Every file assimp opens, for any format it reads (a glTF's buffers and images, an OBJ's
// material libraries and its fallback <name>.mtl, a format's includes): opened only when it
// is a regular file within the scene limit. A FIFO would block the import forever and a
// device never end; assimp cannot tell, so the open fails here instead and the import
// reports it. A missing file is left to assimp (it probes for optional ones).
class BoundedIOSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    std::error_code ec;
    // An OBJ's material libraries are not read: memograph takes a material's graph from its
    // `usemtl` name (assimp keeps the names without the library), nothing from the MTL, and
    // assimp 5.2's MTL reader crashes on malformed libraries (found by the OBJ import
    // fuzzer: a texture before any `newmtl`, stray NUL bytes, an OBJ named as a library).
    // assimp's OBJ parser opens them while it holds the OBJ open, so every open made then
    // is a library, whatever its name. The pre-check has looked at them for the user.
    if (objOnly && !openObjStreams_.empty())
      return nullptr;
    if (std::string_view(mode).find_first_of("wa+") == std::string_view::npos &&
        fs::symlink_status(file, ec).type() != fs::file_type::not_found) {
      std::string error;
      if (!files::checkInputFile(file, files::kMaxSceneFileBytes, "scenes", error)) {
        // assimp may ask again (an OBJ's fallback library is probed twice): said once.
        std::string why = std::string(file) + ": " + error;
        if (std::find(refused.begin(), refused.end(), why) == refused.end())
          refused.push_back(std::move(why));
        return nullptr;
      }
    }
    Assimp::IOStream* stream = Assimp::DefaultIOSystem::Open(file, mode);
    if (objOnly && stream)
      openObjStreams_.insert(stream);
    return stream;
  }
  void Close(Assimp::IOStream* stream) override {
    openObjStreams_.erase(stream);
    Assimp::DefaultIOSystem::Close(stream);
  }
  // DefaultIOSystem::Exists opens the file to see whether it exists, which blocks on a
  // FIFO; a stat does not.
  bool Exists(const char* file) const override {
    std::error_code ec;
    return fs::exists(file, ec);
  }
  std::vector<std::string> refused;
  // An OBJ import: only the OBJ itself is read (see Open).
  bool objOnly = false;

 private:
  std::set<const Assimp::IOStream*> openObjStreams_;
};

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

// The Blender scene export's sidecar (docs/guide/blender.md, "Scene export"): what glTF drops,
// one statement per line, read from <scene stem>.memograph beside the glTF.
struct AreaLight {
  float sizeX = 1.0f, sizeY = 1.0f, power = 0.0f;
  glm::vec3 color{1.0f};
  glm::mat4 objectToWorld{1.0f};  // Blender's matrix_world (z up)
  std::string name;
};
struct TextureSpaceLine {
  glm::vec3 location{0.0f}, size{1.0f};
  std::string mesh;
};
struct Sidecar {
  bool present = false;
  bool zUp = false;
  float lightScale = 1.0f;  // glTF intensity -> W/sr or W/m²: 1 / 683 for lighting SPEC
  std::string camera;
  bool hasWorld = false;
  glm::vec3 worldColor{0.0f};
  float worldStrength = 1.0f;
  std::string worldImage;  // relative to the glTF's folder
  std::vector<TextureSpaceLine> textureSpaces;
  std::vector<AreaLight> areas;
  // material -> emission estimate, and whether it is the material's exact, constant emission
  // (`emitter_constant`: the exporter found its Emission colour and strength unlinked).
  struct Emitter {
    std::string material;
    glm::vec3 emission;
    bool constant = false;
  };
  std::vector<Emitter> emitters;
  float filterGlossy = 0.0f;  // `render filter_glossy F`: Cycles' Filter Glossy; absent: 0
};

std::string restOfLine(std::istringstream& s) {
  std::string rest;
  std::getline(s >> std::ws, rest);
  return rest;
}

bool readSidecar(const std::string& gltfPath, Sidecar& out, compiler::Diagnostics& diagnostics) {
  const fs::path file = fs::path(gltfPath).replace_extension(".memograph");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    return true;
  std::ifstream in(file);
  std::string line;
  int lineNo = 0;
  out.present = true;
  auto bad = [&](const std::string& why) {
    diagnostics.error(file.string(), "line " + std::to_string(lineNo) + ": " + why);
    return false;
  };
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream s(line);
    std::string word;
    s >> word;
    if (lineNo == 1) {
      int version = 0;
      if (word != "memograph-blender-scene" || !(s >> version) || version != 1)
        return bad("expected 'memograph-blender-scene 1'");
    } else if (word == "up") {
      std::string axis;
      s >> axis;
      out.zUp = axis == "z";
    } else if (word == "lighting") {
      std::string mode;
      float lumens = 0.0f;
      if (!(s >> mode))
        return bad("lighting needs a mode");
      if (mode == "SPEC") {
        if (!(s >> lumens) || !(lumens > 0.0f))
          return bad("lighting SPEC needs the lumens per watt");
        out.lightScale = 1.0f / lumens;
      } else if (mode != "COMPAT" && mode != "RAW") {
        return bad("unknown lighting mode '" + mode + "'");
      }
    } else if (word == "camera") {
      out.camera = restOfLine(s);
    } else if (word == "world") {
      std::string kind, strengthWord;
      s >> kind;
      out.hasWorld = true;
      if (kind == "color") {
        if (!(s >> out.worldColor.r >> out.worldColor.g >> out.worldColor.b >> strengthWord >>
              out.worldStrength))
          return bad("world color needs r g b strength s");
      } else if (kind == "image") {
        if (!(s >> strengthWord >> out.worldStrength))
          return bad("world image needs strength s and a path");
        out.worldImage = restOfLine(s);
      } else {
        return bad("unknown world kind '" + kind + "'");
      }
    } else if (word == "render") {
      std::string setting;
      s >> setting;
      if (setting == "filter_glossy") {
        float f = 0.0f;
        if (!(s >> f) || !std::isfinite(f) || f < 0.0f)
          return bad("render filter_glossy needs a number >= 0 (Cycles' Filter Glossy)");
        out.filterGlossy = f;
      }  // other render settings are ignored, as unknown statements are
    } else if (word == "texspace") {
      TextureSpaceLine t;
      if (!(s >> t.location.x >> t.location.y >> t.location.z >> t.size.x >> t.size.y >> t.size.z))
        return bad("texspace needs six numbers and a mesh name");
      t.mesh = restOfLine(s);
      out.textureSpaces.push_back(t);
    } else if (word == "emitter" || word == "emitter_constant") {
      glm::vec3 e;
      if (!(s >> e.r >> e.g >> e.b))
        return bad(word + " needs r g b and a material name");
      out.emitters.push_back({restOfLine(s), e, word == "emitter_constant"});
    } else if (word == "area") {
      AreaLight a;
      std::string shape;
      if (!(s >> shape >> a.sizeX >> a.sizeY >> a.power >> a.color.r >> a.color.g >> a.color.b))
        return bad("area needs shape, two sizes, power and a colour");
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          if (!(s >> a.objectToWorld[c][r]))
            return bad("area needs a 4x4 matrix (16 numbers, column-major)");
      if (shape == "DISK" || shape == "ELLIPSE") {  // a quad of the same area
        a.sizeX *= std::sqrt(glm::pi<float>()) * 0.5f;
        a.sizeY *= std::sqrt(glm::pi<float>()) * 0.5f;
      }
      a.name = restOfLine(s);
      out.areas.push_back(a);
    }  // unknown statements are ignored: later versions may add some
  }
  return true;
}

// Blender's z-up world to memograph's y-up: (x, y, z) -> (x, z, -y), as glTF's +Y up.
glm::mat4 zUpToYUp() {
  return glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0),
                   glm::vec4(0, 0, 0, 1));
}

struct Importer {
  const aiScene& in;
  std::string path;
  std::string materialsDir;
  compiler::Diagnostics& diagnostics;
  Scene scene{};
  std::vector<std::uint32_t> meshMaterial{};       // assimp mesh → scene material
  std::vector<int> meshIndex{};                    // assimp mesh → scene mesh (-1: skipped)
  std::map<std::string, glm::mat4> nodeWorld{};    // node name → world transform
  std::map<unsigned, std::uint32_t> materialOf{};  // assimp material → scene material
  int missingMaterial = -1;
  float lightScale = 1.0f;
  std::string cameraName{};

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
      light.intensity =
          lightScale * glm::vec3{l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b};
      switch (l.mType) {
        case aiLightSource_SPOT: {
          // glTF's cones from Blender's spot size and blend (io_scene_gltf2: outer = size/2,
          // inner = outer (1 - blend)), back to Cycles' spot_angle and spot_smooth.
          light.type = runtime::LightType::Spot;
          light.position =
              glm::vec3(world * glm::vec4(isGltf() ? glm::vec3(0.0f) : toGlm(l.mPosition), 1.0f));
          const glm::vec3 d = glm::vec3(world * glm::vec4(toGlm(l.mDirection), 0.0f));
          light.direction = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, -1, 0);
          const float outer = std::clamp(l.mAngleOuterCone, 1e-4f, glm::pi<float>());
          const float blend = std::clamp((outer - l.mAngleInnerCone) / outer, 0.0f, 1.0f);
          light.spotCosHalfAngle = std::cos(outer);
          light.spotSmooth = (1.0f - light.spotCosHalfAngle) * blend;
          break;
        }
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
    unsigned chosen = 0;
    for (unsigned i = 0; i < in.mNumCameras; ++i)
      if (!cameraName.empty() && cameraName == in.mCameras[i]->mName.C_Str())
        chosen = i;
    const aiCamera& c = *in.mCameras[chosen];
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

// World, texture spaces, area lights (emissive quads) and Filter Glossy from the sidecar.
void applySidecar(Scene& scene, const Sidecar& side, const glm::mat4& root, const fs::path& dir) {
  scene.filterGlossy = side.filterGlossy;
  if (side.hasWorld) {
    if (side.worldImage.empty()) {
      scene.environment.constantRadiance = side.worldColor * side.worldStrength;
    } else {
      scene.environment.imagePath = (dir / side.worldImage).string();
      scene.environment.imageStrength = side.worldStrength;
      // Blender's equirectangular u starts at -x (z up); memograph's at -z (y up): a quarter
      // turn (docs/guide/blender.md).
      scene.environment.imageUOffset = 0.25f;
    }
  }
  for (runtime::Mesh& mesh : scene.meshes) {
    for (const TextureSpaceLine& t : side.textureSpaces) {
      // assimp names a glTF mesh's primitives "<mesh>", "<mesh>-1", ...
      const bool same =
          mesh.name == t.mesh || (mesh.name.size() > t.mesh.size() + 1 &&
                                  mesh.name.starts_with(t.mesh) && mesh.name[t.mesh.size()] == '-');
      if (same) {
        mesh.hasTextureSpace = true;
        mesh.textureSpaceLocation = t.location;
        mesh.textureSpaceSize = t.size;
      }
    }
  }
  for (runtime::MaterialRef& m : scene.materials)
    for (const Sidecar::Emitter& e : side.emitters)
      if (m.name == e.material) {
        m.emissionEstimate = e.emission;
        m.emissionKind = e.constant ? runtime::MaterialRef::EmissionKind::Constant
                                    : runtime::MaterialRef::EmissionKind::Graph;
      }
  for (const AreaLight& a : side.areas) {
    // Cycles 3.4 gives an area light of power P and area A the radiance P / (4 A) on its
    // front (-z) side (measured: docs/guide/blender.md, Light units).
    const float area = std::max(a.sizeX * a.sizeY, 1e-8f);
    runtime::Mesh quad;
    quad.name = "area light " + a.name;
    const float hx = 0.5f * a.sizeX, hy = 0.5f * a.sizeY;
    quad.positions = {{-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}};
    quad.normals.assign(4, glm::vec3(0, 0, -1));
    quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from -z
    runtime::computeTangents(quad);
    scene.meshes.push_back(std::move(quad));
    const glm::vec3 radiance = a.color * (a.power / (4.0f * area));
    const std::string materialName = "mg_area_light_" + std::to_string(scene.materials.size());
    // Front side (-z) only, as Cycles' area lamp: the emission times 1 - Backfacing; black
    // and not specular, so the quad reflects nothing.
    char graph[512];
    std::snprintf(graph, sizeof graph,
                  "material %s;\nBackfacingInput Out>0;\n"
                  "Math Value=1 Value1<0 Value2=0 Operation=1 UseClamp=0 Result>1;\n"
                  "EmissionOutput Color=(%.9g, %.9g, %.9g) Strength<1;\n"
                  "BaseColorOutput In=(0, 0, 0);\nSpecularOutput In=0;\n",
                  materialName.c_str(), radiance.r, radiance.g, radiance.b);
    scene.materials.push_back(runtime::MaterialRef{
        materialName, {}, graph, radiance, runtime::MaterialRef::EmissionKind::ConstantFront});
    scene.instances.push_back(runtime::Instance{
        static_cast<std::uint32_t>(scene.meshes.size() - 1),
        static_cast<std::uint32_t>(scene.materials.size() - 1), root * a.objectToWorld, false});
  }
}

}  // namespace

std::optional<Scene> importScene(const std::string& path, const std::string& materialsDir,
                                 compiler::Diagnostics& diagnostics) {
  std::error_code ec;
  std::string fileError;
  if (!files::checkInputFile(path, files::kMaxSceneFileBytes, "scenes", fileError)) {
    diagnostics.error(path, fileError);
    return std::nullopt;
  }
  // What assimp would trust (declared lengths, indices, hierarchy depth) is checked first.
  if (!precheckGltf(path, diagnostics) || !precheckObj(path, diagnostics))
    return std::nullopt;
  if (!materialsDir.empty() && !fs::is_directory(materialsDir, ec)) {
    diagnostics.error(materialsDir, "the materials folder does not exist");
    return std::nullopt;
  }
  Assimp::Importer importer;
  auto ownedIo = std::make_unique<BoundedIOSystem>();
  BoundedIOSystem* io = ownedIo.get();
  importer.SetIOHandler(ownedIo.release());  // the importer owns it from here
  {
    std::string ext = fs::path(path).extension().string();
    for (char& ch : ext)
      ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    io->objOnly = ext == ".obj";
  }
  // Points and lines are removed; everything else becomes indexed triangles with normals,
  // and tangents wherever there are UVs.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* in = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                aiProcess_CalcTangentSpace | aiProcess_SortByPType |
                aiProcess_ValidateDataStructure | aiProcess_FindInvalidData);
  if (!io->refused.empty()) {
    for (const std::string& refused : io->refused)
      diagnostics.error(path,
                        "the scene reads a file that is not a regular file within the "
                        "limit: " +
                            refused);
    return std::nullopt;
  }
  if (!in) {
    diagnostics.error(path, std::string("cannot import the scene: ") + importer.GetErrorString());
    return std::nullopt;
  }
  if ((in->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !in->mRootNode) {
    diagnostics.error(path, "the scene is incomplete (no node hierarchy or no meshes)");
    return std::nullopt;
  }
  Importer imp{*in, path, materialsDir, diagnostics};
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
  Sidecar sidecar;
  if (imp.isGltf() && !readSidecar(path, sidecar, diagnostics))
    return std::nullopt;
  imp.lightScale = sidecar.lightScale;
  imp.cameraName = sidecar.camera;
  const glm::mat4 root = sidecar.zUp ? zUpToYUp() : glm::mat4(1.0f);
  imp.visit(*in->mRootNode, root);
  if (imp.scene.instances.empty()) {
    diagnostics.error(path, "no node of the scene places a mesh");
    return std::nullopt;
  }
  imp.convertLights();
  imp.convertCamera();
  if (sidecar.present)
    applySidecar(imp.scene, sidecar, root, fs::path(path).parent_path());
  // assimp validated its own structure; this checks what the renderer relies on.
  if (!runtime::validateScene(imp.scene, path, diagnostics))
    return std::nullopt;
  return std::move(imp.scene);
}

}  // namespace memograph::io
