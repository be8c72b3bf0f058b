// A scene pack (.mgpack): an already-imported scene, its camera path and its decoded textures
// in one self-contained binary file of memograph's own format (docs/design/scene-pack.md), so
// that a build without assimp and OpenImageIO (the GPU bundle) renders a glTF/Blender scene.
// Standard library and GLM only; the io module writes packs, every build reads them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/host/image.h"
#include "runtime/scene/scene.h"

namespace memograph::runtime {

// "MGPACK" and two zero bytes, then the format version (little-endian u32).
inline constexpr std::string_view kScenePackMagic{"MGPACK\0\0", 8};
// Version 2 added the scene's Filter Glossy after the emissive light sampling flag.
inline constexpr std::uint32_t kScenePackVersion = 2;
inline constexpr std::string_view kScenePackExtension = ".mgpack";

// A texture as a material graph names it (the graph's own texture path, e.g.
// "textures/wood.png"), with its decoded level 0 (the renderer builds the mip chain).
struct PackedTexture {
  std::string name;
  HdrImage image;
};

struct ScenePack {
  // Materials carry their graph as text (graphText; graphPath empty), so the pack needs no
  // .mgraph beside it; the environment image, if any, is loaded (imageRgb).
  Scene scene;
  std::vector<Camera> cameraPath;  // empty: the pack has none (render uses scene.camera)
  std::vector<PackedTexture> textures;
};

// Whether `path` names a scene pack by its extension (.mgpack, any case).
bool isScenePackPath(const std::filesystem::path& path);

// The pack's bytes: the same pack gives the same bytes. Throws std::invalid_argument for what
// the format does not hold (mesh LODs) or what does not fit its 32-bit counts.
std::string encodeScenePack(const ScenePack& pack);

// Reads a pack's bytes. nullopt with `error` "<displayName>: offset N: <what is wrong>" for a
// bad magic, another version, a truncated or corrupted file (checksum), counts past the
// file's end, or references out of range; never reads past `bytes` nor allocates more than
// the file could hold.
std::optional<ScenePack> decodeScenePack(std::string_view bytes, const std::string& displayName,
                                         std::string& error);

// encodeScenePack written through files::writeFileAtomically (no partial file on failure);
// false with `error` naming the file.
bool writeScenePack(const std::filesystem::path& path, const ScenePack& pack, std::string& error);

// The file read with the input bounds (a regular file of at most files::kMaxSceneFileBytes),
// then decodeScenePack; `error` names the file.
std::optional<ScenePack> readScenePack(const std::filesystem::path& path, std::string& error);

// The texture a material of the pack names, as the renderer's texture loader wants it
// (RendererOptions::textureLoader); throws std::runtime_error when the pack lacks it.
TextureImage packedTexture(const std::vector<PackedTexture>& textures, const std::string& name);

}  // namespace memograph::runtime
