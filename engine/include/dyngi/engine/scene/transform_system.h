#pragma once
#include "dyngi/engine/ecs/scheduler.h"

namespace dyngi::scene {

// Propagates local Transforms into WorldTransforms, touching only the subtrees whose Transform changed
// since its last run, and writing a WorldTransform only when the matrix really changed (so its change
// tick means "moved"). A non-finite local transform keeps the last good world matrix and is reported.
class TransformSystem final : public ecs::System {
 public:
  const char* name() const override { return "transform_propagation"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;

  size_t rejectedNonFinite() const { return rejectedNonFinite_; }
  size_t updatedLastRun() const { return updatedLastRun_; }

 private:
  size_t rejectedNonFinite_ = 0;
  size_t updatedLastRun_ = 0;
};

}  // namespace dyngi::scene
