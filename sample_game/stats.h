#pragma once
// Per-frame timings collected over a run, summarised as medians (and p95 for the frame) in JSON.
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dyngi::sample {

double percentile(std::vector<double> v, double p);  // p in [0,1]; nearest-rank on a sorted copy

// One quantity's per-frame samples over a run, in bounded memory: every sample while there are at most
// kCapacity, then a uniform random subset of kCapacity of all samples seen (reservoir sampling with a
// fixed seed, so a run's summary is reproducible). Medians of short runs are exact; those of long
// windowed sessions are estimated from the subset (rank error about 1/sqrt(kCapacity)), and a session of
// any length holds at most kCapacity doubles per quantity.
class SampleSeries {
 public:
  static constexpr size_t kCapacity = 4096;
  SampleSeries() = default;
  SampleSeries(std::initializer_list<double> values) {
    for (double v : values) push(v);
  }
  void push(double v);
  bool empty() const { return seen_ == 0; }
  uint64_t seen() const { return seen_; }                   // samples pushed over the run
  const std::vector<double>& kept() const { return kept_; }  // at most kCapacity
  double percentile(double p) const { return sample::percentile(kept_, p); }
  double max() const { return max_; }  // over every sample pushed, kept or not

 private:
  std::vector<double> kept_;
  double max_ = 0.0;
  uint64_t seen_ = 0;
  uint64_t rng_ = 0x9E3779B97F4A7C15ull;
};

struct RunStats {
  std::string scene, gi, device;
  std::string stageTimes = "timestamps";  // how stages_ms was timed (--stage-times; the GI budget may fence later frames)
  uint32_t width = 0, height = 0;
  int frames = 0, warmupFrames = 0;
  SampleSeries frameMs;
  std::map<std::string, SampleSeries> gpuStageMs;  // pass name -> per frame
  std::map<std::string, SampleSeries> cpuStageMs;  // system / CPU step -> per frame
  std::map<std::string, double> scalars;                  // counts and sizes
  std::map<std::string, std::map<std::string, double>> sections;  // extra objects, e.g. "vpl": {...}
  std::map<std::string, std::string> namedSettings;  // "settings" entries whose value is a name (--visibility bvh)
  SampleSeries giMs;  // the GI's measured cost per frame (GPU sections + the technique's CPU sections)
  // A GI budget's run: its settings and state at the end, and each change of quality level with the
  // knob values it set ("budget" in the JSON; absent without --gi-budget-ms).
  struct BudgetStep {
    uint64_t frame;
    uint32_t level;
    double medianMs;  // the measured median that led to it
    std::vector<std::pair<std::string, double>> knobs;
  };
  struct Budget {
    double budgetMs = 0;
    bool met = true;
    uint32_t level = 0, floorLevel = 0;
    std::vector<std::pair<std::string, double>> knobs;  // at the end
    std::vector<BudgetStep> trace;
    std::string timing;            // what the controller read: "timestamps" or "fenced" (GiStats::budgetTiming)
    double timestampCoverage = -1;  // the timestamped GI cost over a fenced frame's; -1: not checked
  };
  std::optional<Budget> budget;
  // The playable session at the end ("play" in the JSON; absent when neither a window nor a script ran
  // it): the GI mode, the selection and the last action, so a scripted session can be checked.
  struct Play {
    std::string giMode, selected, lastAction;
    bool scripted = false;
  };
  std::optional<Play> play;

  std::string toJson() const;
  std::string table() const;  // human-readable per-stage medians
};

}  // namespace dyngi::sample
