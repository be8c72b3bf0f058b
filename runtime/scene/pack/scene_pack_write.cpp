// Writes a scene pack (scene_pack.h): the header, then the payload in the order
// docs/design/scene-pack.md lists, every value little-endian.
#include <stdexcept>

#include "runtime/host/atomic_file.h"
#include "runtime/scene/pack/pack_bytes.h"
#include "runtime/scene/pack/scene_pack.h"

namespace memograph::runtime {

namespace {

void writeCamera(pack::ByteWriter& out, const Camera& camera) {
  out.value(camera.position);
  out.value(camera.target);
  out.value(camera.up);
  out.value(camera.verticalFovDegrees);
}

void writeMeshes(pack::ByteWriter& out, const std::vector<Mesh>& meshes) {
  out.count(meshes.size());
  for (const Mesh& mesh : meshes) {
    out.string(mesh.name);
    out.array(mesh.positions);
    out.array(mesh.normals);
    out.array(mesh.uvs);
    out.array(mesh.tangents);
    out.array(mesh.colors);
    out.array(mesh.indices);
    out.u8(mesh.hasTextureSpace);
    out.value(mesh.textureSpaceLocation);
    out.value(mesh.textureSpaceSize);
  }
}

void writeInstances(pack::ByteWriter& out, const std::vector<Instance>& instances) {
  out.count(instances.size());
  for (const Instance& instance : instances) {
    out.value(instance.mesh);
    out.value(instance.material);
    out.value(instance.objectToWorld);
    out.u8(instance.castsShadow);
  }
}

void writeMaterials(pack::ByteWriter& out, const std::vector<MaterialRef>& materials) {
  out.count(materials.size());
  for (const MaterialRef& material : materials) {
    // The pack is self-contained: a graph file's text must have been read into graphText.
    if (material.graphText.empty())
      throw std::invalid_argument("scene pack: material '" + material.name +
                                  "' has no graph text (read its .mgraph into graphText)");
    out.string(material.name);
    out.string(material.graphText);
    out.value(material.emissionEstimate);
    out.value(static_cast<std::uint32_t>(material.emissionKind));
  }
}

void writeLights(pack::ByteWriter& out, const std::vector<Light>& lights) {
  out.count(lights.size());
  for (const Light& light : lights) {
    out.value(static_cast<std::uint32_t>(light.type));
    out.value(light.position);
    out.value(light.direction);
    out.value(light.intensity);
    out.value(light.spotCosHalfAngle);
    out.value(light.spotSmooth);
  }
}

void writeEnvironment(pack::ByteWriter& out, const Environment& environment) {
  out.value(environment.constantRadiance);
  out.string(environment.imagePath);
  out.value(environment.imageStrength);
  out.value(environment.imageUOffset);
  out.value(environment.sunDirection);
  out.value(environment.imageWidth);
  out.value(environment.imageHeight);
  out.array(environment.imageRgb);
}

void writeTextures(pack::ByteWriter& out, const std::vector<PackedTexture>& textures) {
  out.count(textures.size());
  for (const PackedTexture& texture : textures) {
    out.string(texture.name);
    out.value(texture.image.width);
    out.value(texture.image.height);
    out.array(texture.image.rgba);
  }
}

}  // namespace

std::string encodeScenePack(const ScenePack& pack) {
  const Scene& scene = pack.scene;
  if (!scene.meshLods.empty())
    throw std::invalid_argument(
        "scene pack: mesh LODs are not stored (the built-in city builds its own)");
  pack::ByteWriter payload;
  writeMeshes(payload, scene.meshes);
  writeInstances(payload, scene.instances);
  writeMaterials(payload, scene.materials);
  writeLights(payload, scene.lights);
  writeCamera(payload, scene.camera);
  writeEnvironment(payload, scene.environment);
  payload.u8(scene.emissiveLightSampling);
  payload.value(scene.filterGlossy);
  payload.array(scene.animatedMeshes);
  payload.array(scene.animatedMotions);
  payload.count(pack.cameraPath.size());
  for (const Camera& camera : pack.cameraPath)
    writeCamera(payload, camera);
  writeTextures(payload, pack.textures);

  pack::ByteWriter file;
  file.bytes().append(kScenePackMagic);
  file.value(kScenePackVersion);
  file.value(std::uint32_t(0));  // flags: none defined
  file.value(std::uint64_t(payload.bytes().size()));
  file.value(pack::fnv1a64(payload.bytes()));
  file.bytes() += payload.bytes();
  return std::move(file.bytes());
}

bool writeScenePack(const std::filesystem::path& path, const ScenePack& pack, std::string& error) {
  std::string bytes;
  try {
    bytes = encodeScenePack(pack);
  } catch (const std::invalid_argument& e) {
    error = path.string() + ": " + e.what();
    return false;
  }
  if (!files::writeFileAtomically(path, bytes, error)) {
    error = path.string() + ": " + error;
    return false;
  }
  return true;
}

}  // namespace memograph::runtime
