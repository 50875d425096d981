#pragma once
// glTF 2.0 (.gltf / .glb) import into the ECS world and the asset store.
//
// Supported: node hierarchy, skins (JOINTS_0/WEIGHTS_0, inverse bind matrices), node TRS animations, (TRS or matrix), indexed or non-indexed triangle primitives (normals
// generated when absent), pbrMetallicRoughness base colour factor/texture, metallic/roughness factors,
// emissive factor/texture with KHR_materials_emissive_strength, perspective cameras (the first one
// becomes the active camera), KHR_lights_punctual point/spot/directional lights.
//
// Bad input never crashes and never half-populates the world: the file is read and validated in full
// first, and any problem comes back as one line "<file>: <problem>". The content rules (image formats,
// limits, which files a URI may name, value ranges) are in docs/CONTENT.md.
#include <cstdint>
#include <string>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::scene {

struct ImportReport {
  size_t nodes = 0;
  size_t meshInstances = 0;
  size_t triangles = 0;
  size_t lights = 0;
  size_t cameras = 0;
  size_t textures = 0;
  size_t skinnedMeshes = 0;
  std::vector<std::string> clips;   // animation clip names, in file order
  Entity animator{};                // entity holding the Animator (null without animations)
  bool missingClip = false;         // ImportOptions::clip named a clip the file lacks (first one plays)
  Entity activeCamera{};   // null when the file has no camera
  Aabb worldBounds;        // of all mesh instances at import time
  // Extensions the file uses that the import does not honour (optional ones: the file still renders,
  // without them). A required one it does not support fails the import instead.
  std::vector<std::string> ignoredExtensions;
  // What the import did differently from the file, one line each (a material whose textures' transforms
  // differ uses one of them).
  std::vector<std::string> notes;
};
// The glTF extensions the import honours.
const std::vector<std::string>& supportedGltfExtensions();

struct ImportOptions {
  bool markStatic = true;  // tag imported mesh entities StaticTag (DynamicTag otherwise); skinned ones are always dynamic
  std::string clip;        // animation clip to play (empty: the first)
  // Folders beside the scene's own that its URIs may name files in; nothing outside them is opened.
  std::vector<std::string> allowedFolders;
  uint32_t maxImageDimension = 8192;           // texels a side; larger images are refused before decoding
  uint64_t maxImageBytes = uint64_t(1) << 30;  // decoded bytes of all of a file's images together
};

// Returns an empty string on success, else "<path>: <problem>".
std::string importGltf(const std::string& path, ecs::World& world, AssetStore& assets,
                       ImportReport* report = nullptr, const ImportOptions& options = {});

// The same from bytes in memory: a .glb when they start with "glTF", else .gltf text. External URIs
// resolve against `baseDir` and must name files inside it (or options.allowedFolders); `name` stands for
// the file in messages. (The fuzz target's entry point.)
std::string importGltfFromMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                                 ecs::World& world, AssetStore& assets, ImportReport* report = nullptr,
                                 const ImportOptions& options = {});

}  // namespace dyngi::scene
