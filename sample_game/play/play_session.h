#pragma once
// Everything that makes the sample playable, around the frame loop of realtime_run.cpp: the frame's
// input (window or --input-script), the settings panel, picking and dragging, the GI switched at run time,
// screenshots (F12, the script's `screenshot`) and --record.
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/platform/window.h"
#include "dyngi/engine/render/renderer.h"
#include "options.h"
#include "play/gi_control.h"
#include "play/imgui_overlay.h"
#include "play/input.h"
#include "play/interaction.h"
#include "play/panel.h"

namespace dyngi::sample {

class PlaySession {
 public:
  // `gi`: the run's GI system when it started with one; `window` null when headless.
  PlaySession(const Options& o, render::VulkanContext& ctx, render::Renderer& renderer, ecs::Scheduler& scheduler,
              const scene::AssetStore& assets, gi::GiSystem* gi, platform::Window* window, std::optional<InputScript> script);

  // Before the frame's systems: the input, the panel, and what clicks and keys do to the world.
  void beginFrame(uint64_t frame, double dt, ecs::World& world, scene::AssetStore& assets, uint32_t width, uint32_t height);
  // After the frame rendered: the timing graph, screenshots, --record. False when the script says quit.
  bool endFrame(uint64_t frame, const render::RenderSnapshot& snapshot, const render::FrameStats& stats, double frameMs);

  const InputFrame& input() const { return input_; }
  const bool& uiHasMouse() const { return uiHasMouse_; }
  bool paused() const { return play_.paused; }
  bool scripted() const { return script_.has_value(); }
  GiControl& gi() { return gi_; }
  const PlayState& play() const { return play_; }
  int status() const { return status_; }  // 1 when a screenshot could not be written

 private:
  void screenshot(const std::string& path);

  const Options& options_;
  render::Renderer& renderer_;
  platform::Window* window_;
  std::optional<InputScript> script_;
  WindowInput windowInput_;
  InputFrame input_;
  bool uiHasMouse_ = false;
  std::unique_ptr<ImGuiOverlay> ui_;
  bool showPanel_ = true;
  std::map<std::string, glm::dvec2> widgetCentres_;
  GiControl gi_;
  PlayState play_;
  SceneInteraction interaction_;
  TimingHistory timings_;
  render::CameraView lastCamera_;
  bool haveCamera_ = false;
  int screenshots_ = 0;
  int status_ = 0;
};

}  // namespace dyngi::sample
