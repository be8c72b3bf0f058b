// Reads a scene pack (scene_pack.h): the header checked (magic, version, size, checksum)
// before the payload is decoded, every count and reference checked against what is there.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "compiler/input_file.h"
#include "runtime/scene/pack/pack_bytes.h"
#include "runtime/scene/pack/scene_pack.h"

namespace memograph::runtime {

namespace {

using pack::ByteReader;
using pack::PackFormatError;

constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
constexpr std::size_t kCameraBytes = 3 * 12 + 4;

Camera readCamera(ByteReader& in) {
  Camera camera;
  camera.position = in.vec3("camera position");
  camera.target = in.vec3("camera target");
  camera.up = in.vec3("camera up");
  camera.verticalFovDegrees = in.f32("camera field of view");
  return camera;
}

// A per-vertex array must be empty (`optional`) or as long as the positions.
void checkPerVertex(std::size_t at, const Mesh& mesh, std::size_t size, const char* what,
                    bool optional) {
  if (size == mesh.positions.size() || (optional && size == 0))
    return;
  throw PackFormatError(at, "mesh '" + mesh.name + "' has " + std::to_string(size) + " " + what +
                                " for " + std::to_string(mesh.positions.size()) + " vertices");
}

Mesh readMesh(ByteReader& in) {
  const std::size_t at = in.offset();
  Mesh mesh;
  mesh.name = in.string("mesh name");
  mesh.positions = in.array<glm::vec3>("mesh positions");
  mesh.normals = in.array<glm::vec3>("mesh normals");
  mesh.uvs = in.array<glm::vec2>("mesh uvs");
  mesh.tangents = in.array<glm::vec4>("mesh tangents");
  mesh.colors = in.array<glm::vec4>("mesh colors");
  mesh.indices = in.array<std::uint32_t>("mesh indices");
  mesh.hasTextureSpace = in.u8("mesh texture-space flag");
  mesh.textureSpaceLocation = in.vec3("mesh texture-space location");
  mesh.textureSpaceSize = in.vec3("mesh texture-space size");
  checkPerVertex(at, mesh, mesh.normals.size(), "normals", false);
  checkPerVertex(at, mesh, mesh.uvs.size(), "uvs", true);
  checkPerVertex(at, mesh, mesh.tangents.size(), "tangents", true);
  checkPerVertex(at, mesh, mesh.colors.size(), "colors", true);
  if (mesh.indices.size() % 3 != 0)
    throw PackFormatError(at, "mesh '" + mesh.name + "' has " +
                                  std::to_string(mesh.indices.size()) +
                                  " indices, not whole triangles");
  for (const std::uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      throw PackFormatError(at, "mesh '" + mesh.name + "' has index " + std::to_string(index) +
                                    " past its " + std::to_string(mesh.positions.size()) +
                                    " vertices");
  return mesh;
}

template <typename Enum>
Enum readEnum(ByteReader& in, std::uint32_t last, const char* what) {
  const std::size_t at = in.offset();
  const std::uint32_t v = in.u32(what);
  if (v > last)
    throw PackFormatError(at, std::string(what) + " " + std::to_string(v) + " is unknown");
  return static_cast<Enum>(v);
}

void readInstances(ByteReader& in, Scene& scene) {
  const std::uint32_t count = in.count("instances", 4 + 4 + 64 + 1);
  scene.instances.resize(count);
  for (Instance& instance : scene.instances) {
    const std::size_t at = in.offset();
    instance.mesh = in.u32("instance mesh");
    instance.material = in.u32("instance material");
    instance.objectToWorld = in.value<glm::mat4>("instance transform");
    instance.castsShadow = in.u8("instance shadow flag");
    if (instance.mesh >= scene.meshes.size())
      throw PackFormatError(at, "instance mesh " + std::to_string(instance.mesh) + " of " +
                                    std::to_string(scene.meshes.size()) + " meshes");
  }
}

void readMaterials(ByteReader& in, Scene& scene) {
  const std::uint32_t count = in.count("materials", 4 + 4 + 12 + 4);
  scene.materials.resize(count);
  for (MaterialRef& material : scene.materials) {
    const std::size_t at = in.offset();
    material.name = in.string("material name");
    material.graphText = in.string("material graph");
    if (material.graphText.empty())
      throw PackFormatError(at, "material '" + material.name + "' has no graph");
    material.emissionEstimate = in.vec3("material emission estimate");
    material.emissionKind = readEnum<MaterialRef::EmissionKind>(
        in, std::uint32_t(MaterialRef::EmissionKind::ConstantFront), "material emission kind");
  }
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].material >= count)
      throw PackFormatError(in.offset(), "instance " + std::to_string(i) + " names material " +
                                             std::to_string(scene.instances[i].material) + " of " +
                                             std::to_string(count));
}

void readLights(ByteReader& in, Scene& scene) {
  const std::uint32_t count = in.count("lights", 4 + 3 * 12 + 8);
  scene.lights.resize(count);
  for (Light& light : scene.lights) {
    light.type = readEnum<LightType>(in, std::uint32_t(LightType::Spot), "light type");
    light.position = in.vec3("light position");
    light.direction = in.vec3("light direction");
    light.intensity = in.vec3("light intensity");
    light.spotCosHalfAngle = in.f32("spot cone");
    light.spotSmooth = in.f32("spot smoothing");
  }
}

void readEnvironment(ByteReader& in, Environment& environment) {
  environment.constantRadiance = in.vec3("environment radiance");
  environment.imagePath = in.string("environment image name");
  environment.imageStrength = in.f32("environment strength");
  environment.imageUOffset = in.f32("environment u offset");
  environment.sunDirection = in.vec3("environment sun direction");
  const std::size_t at = in.offset();
  environment.imageWidth = in.u32("environment width");
  environment.imageHeight = in.u32("environment height");
  environment.imageRgb = in.array<float>("environment pixels");
  if (environment.imageRgb.size() !=
      std::uint64_t(environment.imageWidth) * environment.imageHeight * 3)
    throw PackFormatError(at, "environment image of " + std::to_string(environment.imageWidth) +
                                  "x" + std::to_string(environment.imageHeight) + " has " +
                                  std::to_string(environment.imageRgb.size()) + " floats");
}

PackedTexture readTexture(ByteReader& in) {
  PackedTexture texture;
  texture.name = in.string("texture name");
  const std::size_t at = in.offset();
  texture.image.width = in.u32("texture width");
  texture.image.height = in.u32("texture height");
  texture.image.rgba = in.array<float>("texture pixels");
  if (texture.image.width == 0 || texture.image.height == 0 ||
      texture.image.rgba.size() != std::uint64_t(texture.image.width) * texture.image.height * 4)
    throw PackFormatError(at, "texture '" + texture.name + "' of " +
                                  std::to_string(texture.image.width) + "x" +
                                  std::to_string(texture.image.height) + " has " +
                                  std::to_string(texture.image.rgba.size()) + " floats");
  return texture;
}

ScenePack decodePayload(ByteReader& in) {
  ScenePack result;
  Scene& scene = result.scene;
  const std::uint32_t meshes = in.count("meshes", 4 * 7 + 1 + 24);
  for (std::uint32_t m = 0; m < meshes; ++m)
    scene.meshes.push_back(readMesh(in));
  readInstances(in, scene);
  readMaterials(in, scene);
  readLights(in, scene);
  scene.camera = readCamera(in);
  readEnvironment(in, scene.environment);
  scene.emissiveLightSampling = in.u8("emissive light sampling flag");
  const std::size_t filterGlossyAt = in.offset();
  scene.filterGlossy = in.f32("Filter Glossy");
  if (!(scene.filterGlossy >= 0.0f) || !std::isfinite(scene.filterGlossy))
    throw PackFormatError(
        filterGlossyAt, "Filter Glossy " + std::to_string(scene.filterGlossy) + " (a number >= 0)");
  const std::size_t animatedAt = in.offset();
  scene.animatedMeshes = in.array<std::uint32_t>("animated meshes");
  scene.animatedMotions = in.array<gpu::VertexMotion>("vertex motions");
  for (const std::uint32_t mesh : scene.animatedMeshes)
    if (mesh >= scene.meshes.size())
      throw PackFormatError(animatedAt, "animated mesh " + std::to_string(mesh) + " of " +
                                            std::to_string(scene.meshes.size()));
  const std::uint32_t cameras = in.count("camera path", kCameraBytes);
  for (std::uint32_t c = 0; c < cameras; ++c)
    result.cameraPath.push_back(readCamera(in));
  const std::uint32_t textures = in.count("textures", 4 + 4 + 4 + 4);
  for (std::uint32_t t = 0; t < textures; ++t)
    result.textures.push_back(readTexture(in));
  if (!in.atEnd())
    throw PackFormatError(in.offset(), "bytes after the last texture");
  return result;
}

}  // namespace

bool isScenePackPath(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension == kScenePackExtension;
}

std::optional<ScenePack> decodeScenePack(std::string_view bytes, const std::string& displayName,
                                         std::string& error) {
  try {
    ByteReader header(bytes.substr(0, std::min(bytes.size(), kHeaderBytes)), 0);
    const auto magic = header.value<std::array<char, 8>>("magic");
    if (std::string_view(magic.data(), magic.size()) != kScenePackMagic)
      throw PackFormatError(0, "not a memograph scene pack (no MGPACK magic)");
    const std::uint32_t version = header.u32("version");
    if (version != kScenePackVersion)
      throw PackFormatError(8, "format version " + std::to_string(version) +
                                   "; this memograph reads version " +
                                   std::to_string(kScenePackVersion) + " (write the pack again)");
    if (const std::uint32_t flags = header.u32("flags"); flags != 0)
      throw PackFormatError(12, "unknown flags " + std::to_string(flags));
    const auto payloadBytes = header.value<std::uint64_t>("payload size");
    const auto checksum = header.value<std::uint64_t>("payload checksum");
    const std::string_view payload = bytes.substr(kHeaderBytes);
    if (payload.size() != payloadBytes)
      throw PackFormatError(bytes.size(),
                            (payload.size() < payloadBytes ? "truncated: " : "") +
                                std::string("the header says ") + std::to_string(payloadBytes) +
                                " payload bytes, the file has " + std::to_string(payload.size()));
    if (pack::fnv1a64(payload) != checksum)
      throw PackFormatError(kHeaderBytes, "corrupt: the payload's checksum does not match");
    ByteReader in(payload, kHeaderBytes);
    return decodePayload(in);
  } catch (const PackFormatError& e) {
    error = displayName + ": offset " + std::to_string(e.offset) + ": " + e.what();
    return std::nullopt;
  }
}

std::optional<ScenePack> readScenePack(const std::filesystem::path& path, std::string& error) {
  const auto bytes = files::readInputFile(path, files::kMaxSceneFileBytes, "scene files", error);
  if (!bytes) {
    error = path.string() + ": " + error;
    return std::nullopt;
  }
  return decodeScenePack(*bytes, path.string(), error);
}

TextureImage packedTexture(const std::vector<PackedTexture>& textures, const std::string& name) {
  for (const PackedTexture& texture : textures)
    if (texture.name == name)
      return TextureImage{{texture.image}};
  throw std::runtime_error("texture '" + name + "' is not in the scene pack");
}

}  // namespace memograph::runtime
