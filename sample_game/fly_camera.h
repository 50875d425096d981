#pragma once
// The windowed sample's camera control: WASD + right-mouse look on the active camera's Transform.
#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/platform/window.h"

namespace dyngi::sample {

class FlyCameraSystem final : public ecs::System {
 public:
  explicit FlyCameraSystem(platform::Window& w) : window_(w) {}
  const char* name() const override { return "fly_camera"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;

 private:
  platform::Window& window_;
  float yaw_ = 0, pitch_ = 0;
  bool initialised_ = false;
};

}  // namespace dyngi::sample
