#include "dyngi/engine/platform/files.h"
#include "play/play_session.h"

#include <GLFW/glfw3.h>

#include <cstdio>

#include "dyngi/engine/render/image_io.h"

namespace dyngi::sample {

PlaySession::PlaySession(const Options& o, render::VulkanContext& ctx, render::Renderer& renderer, ecs::Scheduler& scheduler,
                         const scene::AssetStore& assets, gi::GiSystem* gi, platform::Window* window, std::optional<InputScript> script)
    : options_(o),
      renderer_(renderer),
      window_(window),
      script_(std::move(script)),
      gi_(ctx, renderer, scheduler, assets, gi, o.giSettings, GiControl::modeOf(o.gi)) {
  if (o.showsUi()) {
    ui_ = std::make_unique<ImGuiOverlay>(ctx);
    renderer.addFeature(ui_.get());
  }
  if (gi && o.view != "final") gi_.setView(o.view);
  gi_.setFrameBudget(o.frameBudgetFor(window && !script_));
}

void PlaySession::beginFrame(uint64_t frame, double dt, ecs::World& world, scene::AssetStore& assets, uint32_t width, uint32_t height) {
  if (script_) {
    input_ = script_->frame(frame, [&](const std::string& label) -> std::optional<glm::dvec2> {
      auto it = widgetCentres_.find(label);
      if (it == widgetCentres_.end()) return std::nullopt;
      return it->second;
    });
  } else if (window_) {
    input_ = windowInput_.frame(*window_);
  } else {
    input_ = InputFrame{};
  }
  if (window_ && input_.keyPressed(GLFW_KEY_ESCAPE)) window_->requestClose();
  if (input_.keyPressed(GLFW_KEY_F1)) showPanel_ = !showPanel_;

  uiHasMouse_ = false;
  if (ui_ && showPanel_) {
    ui_->beginFrame(input_, width, height, dt);
    widgetCentres_.clear();
    PanelContext panel{world, gi_, play_, timings_, widgetCentres_};
    drawPanel(panel);
    ui_->endFrame();
    uiHasMouse_ = ui_->wantsMouse();
  }
  if (haveCamera_) interaction_.update(input_, uiHasMouse_, world, assets, lastCamera_, width, height, play_);
}

bool PlaySession::endFrame(uint64_t frame, const render::RenderSnapshot& snapshot, const render::FrameStats& stats, double frameMs) {
  lastCamera_ = snapshot.camera;
  haveCamera_ = true;
  const gi::GiSystem* system = gi_.system();
  timings_.push(frameMs, stats, system ? system->stats().giMs : 0.0);
  gi_.frameFinished(frameMs);
  if (input_.keyPressed(GLFW_KEY_F12)) {
    char name[64];
    std::snprintf(name, sizeof name, "dyngi_screenshot_%03d.png", ++screenshots_);
    screenshot(options_.recordDir.empty() ? name : options_.recordDir + "/" + name);
  }
  if (!options_.recordDir.empty()) {
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%05llu.png", static_cast<unsigned long long>(frame));
    screenshot(options_.recordDir + name);
  }
  bool keepGoing = true;
  if (script_)
    for (const ScriptCommand& c : script_->commandsAt(frame)) {
      if (c.kind == ScriptCommand::Screenshot) screenshot(c.path);
      if (c.kind == ScriptCommand::Quit) keepGoing = false;
      // A window resizes through the window system (the frame loop then recreates the swapchain and the
      // targets, as for a user's drag); headless, the targets are resized here.
      if (c.kind == ScriptCommand::Resize) {
        if (window_) window_->requestSize(c.size.x, c.size.y);
        else renderer_.resize(c.size.x, c.size.y);
      }
    }
  return keepGoing;
}

void PlaySession::screenshot(const std::string& path) {
  const std::string err = render::writePng(path, renderer_.width(), renderer_.height(), renderer_.readbackLdr());
  if (!err.empty()) {
    std::fprintf(stderr, "dyngi_sample: screenshot: %s\n", dyngi::platform::oneLine(err, 1000).c_str());
    status_ = 1;
  }
}

}  // namespace dyngi::sample
