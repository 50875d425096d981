#include "play/panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/components.h"
#include "dyngi/gi/options.h"

namespace dyngi::sample {
namespace {

constexpr float kPanelWidth = 300.0f;

// Remembers the last widget's centre under its visible label (the text before "##").
void remember(PanelContext& p, const std::string& label) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  p.widgetCentres[label.substr(0, label.find("##"))] = {0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
}

void helpTooltip(const char* help) {
  if (help && *help && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", help);
}

double roundToPowerOfTwo(double v) { return v <= 1.0 ? 1.0 : std::exp2(std::round(std::log2(v))); }

// A named-value option: its name, then a radio button per value (remembered as "name value").
bool choiceWidget(PanelContext& p, const gi::OptionRef& r) {
  bool done = false;
  ImGui::TextUnformatted(r.spec->name.c_str());
  helpTooltip(r.spec->help);
  for (size_t i = 0; i < r.spec->choices.size(); ++i) {
    ImGui::SameLine();
    const std::string choice = r.spec->choices[i];
    if (ImGui::RadioButton((choice + "##" + r.spec->name).c_str(), r.get() == double(i))) r.set(double(i)), done = true;
    remember(p, r.spec->name + " " + choice);
  }
  return done;
}

// One option from a technique's table: a checkbox, radio buttons, an integer slider or a float drag over
// its range. Returns true when an edit ended (the GI is rebuilt then, not on every step of a drag).
bool optionWidget(PanelContext& p, const gi::OptionRef& r) {
  if (r.isChoice()) return choiceWidget(p, r);
  const std::string label = r.spec->name;
  bool done = false;
  if (r.isBool()) {
    bool v = r.get() != 0.0;
    if (ImGui::Checkbox(label.c_str(), &v)) r.set(v ? 1.0 : 0.0), done = true;
  } else if (r.isInteger() && r.spec->max - r.spec->min <= 1 << 20) {
    int v = int(r.get());
    ImGui::SliderInt(label.c_str(), &v, int(r.spec->min), int(r.spec->max), "%d", ImGuiSliderFlags_AlwaysClamp);
    double value = r.spec->powerOfTwo ? roundToPowerOfTwo(v) : v;
    r.set(std::clamp(value, r.spec->min, r.spec->max));
    done = ImGui::IsItemDeactivatedAfterEdit();
  } else {
    float v = float(r.get());
    const float speed = float(std::max(1e-4, (r.spec->max - r.spec->min) / 500.0));
    ImGui::DragFloat(label.c_str(), &v, speed, float(r.spec->min), float(r.spec->max), "%.3g", ImGuiSliderFlags_AlwaysClamp);
    r.set(std::clamp(double(v), r.spec->min, r.spec->max));
    done = ImGui::IsItemDeactivatedAfterEdit();
  }
  remember(p, label);
  helpTooltip(r.spec->help);
  return done;
}

// The GI budget as it runs: the level on its ladder, each knob's value now, what the cost is read from.
void budgetStatus(const gi::GiSystem& system) {
  const gi::BudgetController* b = system.budget();
  if (!b) return;
  const gi::GiStats st = system.stats();
  ImGui::Text("GI budget %.1f ms: level %u of %u", b->budgetMs(), b->level(), b->floorLevel());
  ImGui::Text("  %s", b->budgetMet() ? "met" : "not met, every knob at its floor");
  for (const auto& [knob, value] : b->knobValues()) ImGui::Text("  %s %g", knob.c_str(), value);
  if (!st.budgetTiming.empty()) ImGui::TextDisabled("  cost: %s (stamps held %.2f)", st.budgetTiming.c_str(), st.timestampCoverage);
}

void giSection(PanelContext& p) {
  ImGui::TextUnformatted("Global illumination");
  for (const std::string& m : GiControl::modes()) {
    if (&m != &GiControl::modes().front()) ImGui::SameLine();
    if (ImGui::RadioButton(m.c_str(), p.gi.mode() == m)) p.gi.setMode(m);
    remember(p, m);
  }
  gi::GiSystem* system = p.gi.system();
  if (!system) return;
  const gi::TechniqueEntry& entry = system->techniqueEntry();
  ImGui::TextDisabled("%s: %s", entry.name, entry.summary);
  if (ImGui::BeginCombo("view", p.gi.view().c_str())) {
    std::vector<std::string> views = {"final"};
    for (const char* v : entry.debugViews) views.push_back(v);
    for (const std::string& v : views) {
      if (ImGui::Selectable(v.c_str(), v == p.gi.view())) p.gi.setView(v);
      remember(p, "view " + v);
    }
    ImGui::EndCombo();
  }
  remember(p, "view");
  // The frame budget (--frame-budget-ms): the GI budget below follows what the rest of the frame leaves.
  float frameBudget = float(p.gi.frameBudget().target());
  if (ImGui::DragFloat("frame budget", &frameBudget, 1.0f, 0.0f, 1000.0f, frameBudget > 0.0f ? "%.0f ms" : "off", ImGuiSliderFlags_AlwaysClamp) &&
      double(frameBudget) != p.gi.frameBudget().target())
    p.gi.setFrameBudget(frameBudget);
  remember(p, "frame budget");
  helpTooltip("hold the whole frame near this by giving the GI budget what the rest of the frame leaves (0: off)");
  budgetStatus(*system);
  if (ImGui::CollapsingHeader("Technique options", ImGuiTreeNodeFlags_DefaultOpen)) {
    bool changed = false;
    for (const gi::OptionRef& r : entry.options(p.gi.settings())) changed |= optionWidget(p, r);
    if (ImGui::TreeNode("Voxel scene and GI budget")) {
      for (const gi::OptionRef& r : gi::bindOptions(p.gi.settings().voxels)) changed |= optionWidget(p, r);
      for (const gi::OptionRef& r : gi::bindOptions(p.gi.settings().budget)) changed |= optionWidget(p, r);
      ImGui::TreePop();
    }
    if (changed) p.gi.apply();
  }
}

void plot(const char* label, const std::deque<float>& values) {
  if (values.empty()) return;
  std::vector<float> v(values.begin(), values.end());
  const float top = *std::max_element(v.begin(), v.end());
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%s %.1f ms", label, double(v.back()));
  ImGui::PlotLines("##plot", v.data(), int(v.size()), 0, overlay, 0.0f, top * 1.1f + 1e-3f, ImVec2(-1, 48));
}

void timingSection(PanelContext& p) {
  if (!ImGui::CollapsingHeader("Timing")) return;
  ImGui::PushID("frame");
  plot("frame", p.timings.frameMs());
  ImGui::PopID();
  ImGui::PushID("gi");
  plot("GI", p.timings.giMs());
  ImGui::PopID();
  if (ImGui::BeginTable("stages", 2, ImGuiTableFlags_RowBg)) {
    for (const auto& [name, ms] : p.timings.sectionMedians()) {
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%7.2f ms", ms);
    }
    ImGui::EndTable();
  }
}

void lightsSection(PanelContext& p) {
  if (!ImGui::CollapsingHeader("Lights")) return;
  std::vector<ecs::Entity> lights;
  p.world.each<scene::Light>([&](ecs::Entity e, const scene::Light&) { lights.push_back(e); });
  for (ecs::Entity e : lights) {
    ImGui::PushID(int(e.index));
    scene::Light l = p.world.get<scene::Light>(e);
    const scene::Light before = l;
    const std::string name = entityLabel(p.world, e);
    ImGui::Checkbox(name.c_str(), &l.enabled);
    remember(p, name);
    ImGui::SameLine();
    if (ImGui::SmallButton("select")) p.play.selected = e;
    ImGui::ColorEdit3("colour", &l.color.x, ImGuiColorEditFlags_NoInputs);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(100);
    ImGui::DragFloat("intensity", &l.intensity, 0.05f, 0.0f, 1000.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    if (l.type == scene::LightType::Spot) {
      float outer = glm::degrees(l.outerConeAngle), inner = glm::degrees(l.innerConeAngle);
      ImGui::DragFloat("outer cone", &outer, 0.2f, 1.0f, 89.0f, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
      ImGui::DragFloat("inner cone", &inner, 0.2f, 0.0f, outer, "%.1f deg", ImGuiSliderFlags_AlwaysClamp);
      l.outerConeAngle = glm::radians(outer);
      l.innerConeAngle = glm::radians(std::min(inner, outer));
    }
    // Written only when a value changed: a write is a change the GI reacts to.
    if (l.enabled != before.enabled || l.color != before.color || l.intensity != before.intensity ||
        l.outerConeAngle != before.outerConeAngle || l.innerConeAngle != before.innerConeAngle)
      p.world.write<scene::Light>(e) = l;
    ImGui::Separator();
    ImGui::PopID();
  }
}

void selectionSection(PanelContext& p) {
  if (!ImGui::CollapsingHeader("Selection", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const ecs::Entity e = p.play.selected;
  if (e.isNull() || !p.world.alive(e)) {
    ImGui::TextDisabled("click an object or a light to select it");
    return;
  }
  ImGui::Text("%s", entityLabel(p.world, e).c_str());
  if (p.world.has<scene::Transform>(e)) {
    scene::Transform t = p.world.get<scene::Transform>(e);
    const scene::Transform before = t;
    ImGui::DragFloat3("position", &t.translation.x, 0.01f);
    float yaw = glm::degrees(glm::eulerAngles(t.rotation).y);
    if (ImGui::DragFloat("turn", &yaw, 0.5f, -180.0f, 180.0f, "%.1f deg")) {
      const glm::vec3 euler = glm::eulerAngles(t.rotation);
      t.rotation = glm::quat(glm::vec3(euler.x, glm::radians(yaw), euler.z));
    }
    float s = t.scale.x;
    if (ImGui::DragFloat("scale", &s, 0.01f, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp) && t.scale.x > 0.0f) t.scale *= s / t.scale.x;
    if (t.translation != before.translation || t.rotation != before.rotation || t.scale != before.scale) p.world.write<scene::Transform>(e) = t;
  }
  if (p.world.has<scene::Material>(e)) {
    scene::Material m = p.world.get<scene::Material>(e);
    const scene::Material before = m;
    ImGui::ColorEdit3("base colour", &m.baseColor.x, ImGuiColorEditFlags_Float);
    float strength = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
    glm::vec3 hue = strength > 0.0f ? m.emissive / strength : glm::vec3(1.0f);
    ImGui::ColorEdit3("emission colour", &hue.x, ImGuiColorEditFlags_NoInputs);
    ImGui::DragFloat("emission", &strength, 0.05f, 0.0f, 100.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    m.emissive = hue * strength;
    if (m.baseColor != before.baseColor || m.emissive != before.emissive) p.world.write<scene::Material>(e) = m;
  }
}

}  // namespace

void TimingHistory::push(double frameMs, const render::FrameStats& stats, double giMs) {
  auto add = [](std::deque<float>& d, double v) {
    d.push_back(float(v));
    if (d.size() > kFrames) d.pop_front();
  };
  add(frame_, frameMs);
  add(gi_, std::max(0.0, giMs));
  order_.clear();
  std::map<std::string, double> perPass;  // a pass recorded twice a frame counts once
  for (const auto& [name, ms] : stats.gpuMs) {
    if (!perPass.count(name)) order_.push_back(name);
    perPass[name] += ms;
  }
  for (const auto& [name, ms] : perPass) add(sections_[name], ms);
}

std::vector<std::pair<std::string, double>> TimingHistory::sectionMedians() const {
  std::vector<std::pair<std::string, double>> out;
  for (const std::string& name : order_) {
    std::vector<float> v(sections_.at(name).begin(), sections_.at(name).end());
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    out.push_back({name, v[v.size() / 2]});
  }
  return out;
}

void drawPanel(PanelContext& p) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  // Its own height, at most the view's: a long one scrolls.
  ImGui::SetNextWindowSizeConstraints(ImVec2(kPanelWidth, 0), ImVec2(kPanelWidth, std::max(100.0f, ImGui::GetIO().DisplaySize.y - 16)));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("dyngi", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushItemWidth(150);  // the rest of the width for the labels
  const auto& f = p.timings.frameMs();
  ImGui::Text("%.1f ms a frame%s", f.empty() ? 0.0 : double(f.back()), p.play.paused ? "  (paused: P)" : "");
  giSection(p);
  selectionSection(p);
  lightsSection(p);
  timingSection(p);
  if (ImGui::CollapsingHeader("Keys")) {
    ImGui::TextUnformatted(
        "click: select    drag: move    R / shift+R: turn\n= / -: scale (light: intensity)    DELETE: remove\n"
        "B: drop a box    L: drop a light    P: pause motion\nright drag: look    WASD QE: fly    F1: panel    F12: screenshot");
  }
  if (!p.play.lastAction.empty()) ImGui::TextDisabled("%s", p.play.lastAction.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace dyngi::sample
