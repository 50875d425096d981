#pragma once
// The settings panel (Dear ImGui), built every frame: the GI mode, every option of the active technique
// from its option table, the debug view, a timing graph, the lights, and the selected object.
#include <deque>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/render/renderer.h"
#include "play/gi_control.h"
#include "play/interaction.h"

namespace dyngi::sample {

// The last seconds of timings, for the graph: frame and GI milliseconds, and each GPU section's.
class TimingHistory {
 public:
  static constexpr size_t kFrames = 240;
  void push(double frameMs, const render::FrameStats& stats, double giMs);
  const std::deque<float>& frameMs() const { return frame_; }
  const std::deque<float>& giMs() const { return gi_; }
  // Each GPU section's median over the history (ms), in recording order of the last frame.
  std::vector<std::pair<std::string, double>> sectionMedians() const;

 private:
  std::deque<float> frame_, gi_;
  std::map<std::string, std::deque<float>> sections_;
  std::vector<std::string> order_;
};

struct PanelContext {
  ecs::World& world;
  GiControl& gi;
  PlayState& play;
  const TimingHistory& timings;
  // Each widget's centre as drawn this frame, by its visible label: where an input script's `ui LABEL`
  // clicks next frame.
  std::map<std::string, glm::dvec2>& widgetCentres;
};

void drawPanel(PanelContext& p);

}  // namespace dyngi::sample
