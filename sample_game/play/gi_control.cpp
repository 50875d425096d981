#include "play/gi_control.h"

#include "options.h"

namespace dyngi::sample {

GiControl::GiControl(render::VulkanContext& ctx, render::Renderer& renderer, ecs::Scheduler& scheduler, const scene::AssetStore& assets,
                     gi::GiSystem* existing, const gi::GiSettings& settings, std::string mode)
    : ctx_(ctx), renderer_(renderer), scheduler_(scheduler), assets_(assets), system_(existing), settings_(settings), mode_(std::move(mode)) {}

const std::vector<std::string>& GiControl::modes() {
  static const std::vector<std::string> m = [] {
    std::vector<std::string> all;
    for (const std::string& mode : giModes())
      if (mode == "off" || isTechniqueMode(mode)) all.push_back(mode);
    return all;
  }();
  return m;
}

std::string GiControl::modeOf(const std::string& gi) { return isTechniqueMode(gi) ? gi : "off"; }

void GiControl::setMode(const std::string& mode) {
  if (mode == mode_) return;
  mode_ = mode;
  if (mode == "off") {
    if (system_) system_->detach();
    return;
  }
  settings_.technique = mode;
  view_ = "final";  // another technique's views are not this one's
  if (!system_) {
    auto made = std::make_unique<gi::GiSystem>(ctx_, assets_, settings_);
    system_ = made.get();
    system_->attach(renderer_);
    scheduler_.add(ecs::Phase::PostUpdate, std::move(made));  // after transforms and skinning, as at start-up
    return;
  }
  system_->reset(settings_);  // one rebuild, then (when the GI was off) its features back in the renderer
  if (!system_->attached()) system_->attach(renderer_);
}

void GiControl::apply() {
  if (system_ && system_->attached()) {
    system_->reset(settings_);
    system_->setDebugView(view_);
  }
}

void GiControl::setFrameBudget(double targetMs) {
  const bool wasOn = frameBudget_.target() > 0.0;
  frameBudget_.setTarget(targetMs);
  if (wasOn && !(frameBudget_.target() > 0.0)) {
    settings_.budget.budgetMs = 0.0f;
    if (system_) system_->setBudgetMs(0.0);
  }
}

void GiControl::frameFinished(double frameMs) {
  gi::GiSystem* s = system();
  if (!s || !(frameBudget_.target() > 0.0)) return;
  double budget = frameBudget_.onFrame(frameMs, s->stats().giMs);
  if (budget == 0.0 && !s->budget() && frameBudget_.giBudget() > 0.0) budget = frameBudget_.giBudget();  // a rebuild started without it
  if (budget > 0.0) {
    s->setBudgetMs(budget);
    settings_.budget.budgetMs = float(budget);  // what a rebuild (another technique, an edit) starts from
  }
}

bool GiControl::setView(const std::string& view) {
  if (!system() || !system_->setDebugView(view)) return false;
  view_ = view;
  return true;
}

}  // namespace dyngi::sample
