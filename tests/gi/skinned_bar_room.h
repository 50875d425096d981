#pragma once
// The Cornell box with the two-bone skinned bar (tests/support/skinned_bar.h) standing at `base`, and the
// systems that bend it, for the GI tests that follow a deforming mesh.
#include <gtest/gtest.h>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/scene/animation.h"
#include "scenes/builtin_scenes.h"
#include "support/skinned_bar.h"

namespace dyngi::test {

struct SkinnedBarRoom {
  ecs::World world;
  scene::AssetStore assets;
  TempDir dir;
  SkinnedBar bar;
  ecs::Scheduler scheduler;  // animation, transforms, skinning; a test adds its GI systems after them
  scene::MeshId deformed = 0;

  explicit SkinnedBarRoom(const glm::vec3& base) {
    sample::buildBuiltinScene("cornell", world, assets);
    bar = addSkinnedBar(world, assets, dir, base);
    addAnimationAndSkinning(scheduler, assets);
    if (bar.error.empty()) deformed = world.get<scene::SkinnedMesh>(bar.mesh).deformed;
  }
};

}  // namespace dyngi::test
