#pragma once
// The ECS system that keeps an EmbreeScene in step with the world: run it after transform propagation
// and skinning. It reads only what changed since its last run (change ticks).
#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/gi/bvh.h"

namespace dyngi::gi {

class BvhSyncSystem final : public ecs::System {
 public:
  BvhSyncSystem(EmbreeScene& bvh, const scene::AssetStore& assets) : bvh_(bvh), assets_(assets) {}
  const char* name() const override { return "bvh_update"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override { bvh_.sync(world, assets_, ctx.lastRun); }

 private:
  EmbreeScene& bvh_;
  const scene::AssetStore& assets_;
};

}  // namespace dyngi::gi
