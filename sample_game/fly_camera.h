#pragma once
// The windowed sample's camera control: WASD QE + right-mouse look on the active camera's Transform,
// from the frame's input (the window's or an input script's).
#include "dyngi/engine/ecs/scheduler.h"
#include "play/input.h"

namespace dyngi::sample {

class FlyCameraSystem final : public ecs::System {
 public:
  // `input` and `uiHasMouse` are the frame loop's, updated before each run.
  FlyCameraSystem(const InputFrame& input, const bool& uiHasMouse) : input_(input), uiHasMouse_(uiHasMouse) {}
  const char* name() const override { return "fly_camera"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;

 private:
  const InputFrame& input_;
  const bool& uiHasMouse_;
  float yaw_ = 0, pitch_ = 0;
  bool initialised_ = false;
};

}  // namespace dyngi::sample
