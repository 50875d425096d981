#include "stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

namespace dyngi::sample {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");  // nothing timed: null in JSON, not a zero that reads as "free"
  std::sort(v.begin(), v.end());
  if (p == 0.5) {  // exact median (mean of the middle pair for even counts)
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }
  size_t rank = size_t(std::ceil(p * double(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

void SampleSeries::push(double v) {
  max_ = seen_ == 0 ? v : std::max(max_, v);
  ++seen_;
  if (kept_.size() < kCapacity) {
    if (kept_.capacity() == 0) kept_.reserve(kCapacity);  // all at once: a run's memory is flat from its first frame
    kept_.push_back(v);
    return;
  }
  // Algorithm R: the seen_-th sample replaces a random kept one with probability kCapacity / seen_.
  rng_ ^= rng_ << 13, rng_ ^= rng_ >> 7, rng_ ^= rng_ << 17;  // xorshift64
  uint64_t slot = rng_ % seen_;
  if (slot < kCapacity) kept_[size_t(slot)] = v;
}

namespace {
// A number, or null for "not measured" (NaN: nothing timed), never a zero that reads as "free".
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

std::string RunStats::toJson() const {
  nlohmann::ordered_json j;
  j["scene"] = scene;
  j["size"] = {width, height};
  j["gi"] = gi;
  j["device"] = device;
  j["frames"] = frames;
  j["warmup_frames"] = warmupFrames;
  j["frame_ms"] = {{"median", number(frameMs.percentile(0.5))}, {"p95", number(frameMs.percentile(0.95))}, {"max", number(frameMs.max())}};
  auto medians = [](const std::map<std::string, SampleSeries>& m) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (auto& [name, v] : m) o[name] = number(v.percentile(0.5));
    return o;
  };
  j["stage_times"] = stageTimes;
  j["stages_ms"] = medians(gpuStageMs);
  j["cpu_ms"] = medians(cpuStageMs);
  j["counts"] = nlohmann::ordered_json::object();
  for (auto& [name, v] : scalars) j["counts"][name] = number(v);
  for (auto& [key, values] : sections) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (auto& [name, v] : values) o[name] = number(v);
    j[key] = o;
  }
  for (auto& [name, value] : namedSettings) j["settings"][name] = value;
  if (play) j["play"] = {{"gi_mode", play->giMode}, {"selected", play->selected}, {"last_action", play->lastAction}, {"scripted", play->scripted}};
  if (!giMs.empty())
    j["gi_ms"] = {{"median", number(giMs.percentile(0.5))}, {"p95", number(giMs.percentile(0.95))}, {"max", number(giMs.max())}};
  if (budget) {
    auto knobs = [](const std::vector<std::pair<std::string, double>>& values) {
      nlohmann::ordered_json o = nlohmann::ordered_json::object();
      for (auto& [name, v] : values) o[name] = number(v);
      return o;
    };
    nlohmann::ordered_json b;
    b["budget_ms"] = budget->budgetMs;
    b["met"] = budget->met;
    b["level"] = budget->level;
    b["floor_level"] = budget->floorLevel;
    b["knobs"] = knobs(budget->knobs);
    b["timing"] = budget->timing;
    b["timestamp_coverage"] = number(budget->timestampCoverage);
    b["trace"] = nlohmann::ordered_json::array();
    for (const BudgetStep& step : budget->trace)
      b["trace"].push_back({{"frame", step.frame}, {"level", step.level}, {"median_ms", number(step.medianMs)}, {"knobs", knobs(step.knobs)}});
    j["budget"] = b;
  }
  // Invalid UTF-8 (a scene path from the command line) is replaced, not thrown.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string RunStats::table() const {
  std::ostringstream t;
  char line[160];
  std::snprintf(line, sizeof line, "%s %ux%u gi=%s on %s: %d frames (%d warm-up)\n", scene.c_str(), width, height, gi.c_str(),
                device.c_str(), frames, warmupFrames);
  t << line;
  std::snprintf(line, sizeof line, "  %-24s %10s\n", "stage", "median ms");
  t << line;
  for (auto& [name, v] : gpuStageMs) {
    std::snprintf(line, sizeof line, "  gpu %-20s %10.3f\n", name.c_str(), v.percentile(0.5));
    t << line;
  }
  for (auto& [name, v] : cpuStageMs) {
    std::snprintf(line, sizeof line, "  cpu %-20s %10.3f\n", name.c_str(), v.percentile(0.5));
    t << line;
  }
  if (frameMs.empty()) std::snprintf(line, sizeof line, "  no frame timed: the run ended within the %d warm-up frames\n", warmupFrames);
  else std::snprintf(line, sizeof line, "  frame (median / p95)    %10.3f / %.3f\n", frameMs.percentile(0.5), frameMs.percentile(0.95));
  t << line;
  if (!giMs.empty()) {
    std::snprintf(line, sizeof line, "  gi (median / p95)       %10.3f / %.3f\n", giMs.percentile(0.5), giMs.percentile(0.95));
    t << line;
  }
  if (budget) {
    auto knobValue = [](double v) {  // counts as integers, fractions as they are (1/16: 0.0625)
      char text[32];
      std::snprintf(text, sizeof text, "%g", v);
      return std::string(text);
    };
    std::string knobs;
    for (auto& [name, v] : budget->knobs) knobs += " " + name + " " + knobValue(v);
    std::snprintf(line, sizeof line, "  gi budget %.3f ms: %s, level %u of %u, %zu changes, at the end%s\n", budget->budgetMs,
                  budget->met ? "met" : "NOT met at the floor", budget->level, budget->floorLevel, budget->trace.size(), knobs.c_str());
    t << line;
    for (const BudgetStep& step : budget->trace) {
      std::string values;
      for (auto& [name, v] : step.knobs) values += " " + name + " " + knobValue(v);
      std::snprintf(line, sizeof line, "    frame %4llu: level %2u after a median of %7.2f ms:%s\n", (unsigned long long)step.frame, step.level,
                    step.medianMs, values.c_str());
      t << line;
    }
  }
  return t.str();
}

}  // namespace dyngi::sample
