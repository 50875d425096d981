#include "stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

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
std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += c;
    else if (c == '\n') o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o;
}
std::string num(double v) {
  char buf[64];
  if (!std::isfinite(v)) return "null";
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}
}  // namespace

std::string RunStats::toJson() const {
  std::ostringstream j;
  j << "{\n";
  j << "  \"scene\": \"" << escape(scene) << "\",\n";
  j << "  \"size\": [" << width << ", " << height << "],\n";
  j << "  \"gi\": \"" << escape(gi) << "\",\n";
  j << "  \"device\": \"" << escape(device) << "\",\n";
  j << "  \"frames\": " << frames << ",\n";
  j << "  \"warmup_frames\": " << warmupFrames << ",\n";
  j << "  \"frame_ms\": {\"median\": " << num(frameMs.percentile(0.5)) << ", \"p95\": " << num(frameMs.percentile(0.95)) << "},\n";
  auto section = [&](const char* key, const std::map<std::string, SampleSeries>& m, bool last) {
    j << "  \"" << key << "\": {";
    bool first = true;
    for (auto& [name, v] : m) {
      j << (first ? "" : ", ") << "\"" << escape(name) << "\": " << num(v.percentile(0.5));
      first = false;
    }
    j << "}" << (last ? "\n" : ",\n");
  };
  section("stages_ms", gpuStageMs, false);
  section("cpu_ms", cpuStageMs, false);
  j << "  \"counts\": {";
  bool first = true;
  for (auto& [name, v] : scalars) {
    j << (first ? "" : ", ") << "\"" << escape(name) << "\": " << num(v);
    first = false;
  }
  j << "}";
  for (auto& [key, values] : sections) {
    j << ",\n  \"" << escape(key) << "\": {";
    bool firstValue = true;
    for (auto& [name, v] : values) {
      j << (firstValue ? "" : ", ") << "\"" << escape(name) << "\": " << num(v);
      firstValue = false;
    }
    j << "}";
  }
  j << "\n}\n";
  return j.str();
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
  return t.str();
}

}  // namespace dyngi::sample
