#pragma once
// A 4 m floor under a 2 m horizontal "fence" 1 m above it whose left half (x < 0) its base colour's
// alpha cuts away (alphaMode MASK, cutoff 0.5), lit from above by the sun; the camera looks down from
// the side. The alpha-mask tests' scene: the raster passes, the path tracer, the VPLs and picking.
#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::test {

constexpr float kFenceHeight = 1.0f;
const glm::vec3 kFenceSunDirection{0.15f, -1.0f, 0.1f};  // the sun's rays (not unit)

struct FenceScene {
  ecs::Entity floor, fence, sun, camera;
};
FenceScene floorUnderAFence(ecs::World& world, scene::AssetStore& assets);

// Where the sun's ray down to floor point p crosses the fence's plane: over its cut half, its solid
// half, or beside it.
enum class Under { Hole, Solid, Open };
Under underTheFence(const glm::vec3& p);

}  // namespace dyngi::test
