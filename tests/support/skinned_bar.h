#pragma once
// A two-bone skinned mesh built in code and loaded through the real glTF importer, for the GI tests
// that must see a mesh deform (BVH refit, re-voxelization, VPL invalidation) without ../shared.
//
// The bar is a 0.16 x 1.2 x 0.16 box standing on `base`, cut into 12 rings along its height. Its lower
// half follows the root joint, its upper half a second joint 0.6 above it (the ring between them is
// weighted half and half), and the animation "bend" turns that joint about +Z from 0 to 90 degrees
// between t = 0 and t = 1 s, so the bar folds over sideways towards -X.
#include <string>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "support/gltf_writer.h"
#include "support/temp_dir.h"

namespace dyngi::test {

struct SkinnedBar {
  ecs::Entity mesh;      // the skinned mesh instance
  ecs::Entity animator;  // plays "bend"
  std::string error;     // empty when the import worked
};

// The bar as a glTF of its own: mesh 0, material 0, nodes 0 (the mesh) to 2 (the joints), skin 0, and
// the animation "bend".
GltfSpec skinnedBarSpec(const glm::vec3& base, const glm::vec3& baseColor = glm::vec3(0.8f));
// `scene` with the bar added (its meshes, nodes, skin, material and animation renumbered after scene's).
GltfSpec withSkinnedBar(GltfSpec scene, const glm::vec3& base, const glm::vec3& baseColor = glm::vec3(0.8f));

// Imports the bar into `world` with material `baseColor`.
SkinnedBar addSkinnedBar(ecs::World& world, scene::AssetStore& assets, const TempDir& dir, const glm::vec3& base,
                         const glm::vec3& baseColor = glm::vec3(0.8f));

// The systems that make it bend: animation (Update), then transform propagation and skinning
// (PostUpdate). A GI system added after them sees each frame's deformed mesh.
void addAnimationAndSkinning(ecs::Scheduler& scheduler, scene::AssetStore& assets);

}  // namespace dyngi::test
