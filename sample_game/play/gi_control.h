#pragma once
// The GI of a run that changes while it runs: the panel's mode (off or a technique), the settings
// of the active technique, and the debug view, applied between frames through GiSystem::reset,
// detach and attach. The GI system is made the first time a mode needs it and then lives in the
// scheduler like any system.
#include <string>
#include <vector>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/gi/gi_system.h"
#include "play/frame_budget.h"

namespace dyngi::sample {

class GiControl {
 public:
  // `existing`: the run's GI system when it started with one (already attached and scheduled).
  GiControl(render::VulkanContext& ctx, render::Renderer& renderer, ecs::Scheduler& scheduler, const scene::AssetStore& assets,
            gi::GiSystem* existing, const gi::GiSettings& settings, std::string mode);

  static const std::vector<std::string>& modes();  // off and every technique: the --gi values but path
  static std::string modeOf(const std::string& gi);  // the mode a --gi value starts in


  const std::string& mode() const { return mode_; }
  void setMode(const std::string& mode);  // a name from modes()
  // The settings the panel edits; apply() hands them to the GI (a rebuild: call when an edit ends).
  gi::GiSettings& settings() { return settings_; }
  void apply();
  gi::GiSystem* system() const { return mode_ == "off" ? nullptr : system_; }
  gi::GiSystem* everMade() const { return system_; }  // for the run's stats, even when switched off
  const std::string& view() const { return view_; }
  bool setView(const std::string& view);
  // The frame budget (0: off), and each rendered frame's wall-clock milliseconds for it: the GI's budget
  // follows what the rest of the frame leaves.
  const FrameBudget& frameBudget() const { return frameBudget_; }
  // 0 turns it off and the GI budget with it.
  void setFrameBudget(double targetMs);
  void frameFinished(double frameMs);

 private:
  render::VulkanContext& ctx_;
  render::Renderer& renderer_;
  ecs::Scheduler& scheduler_;
  const scene::AssetStore& assets_;
  gi::GiSystem* system_ = nullptr;  // owned by the scheduler
  gi::GiSettings settings_;
  std::string mode_;
  std::string view_ = "final";
  FrameBudget frameBudget_;
};

}  // namespace dyngi::sample
