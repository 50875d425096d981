#pragma once
// Per-frame timings collected over a run, summarised as medians (and p95 for the frame) in JSON.
#include <map>
#include <string>
#include <vector>

namespace dyngi::sample {

double percentile(std::vector<double> v, double p);  // p in [0,1]; nearest-rank on a sorted copy

struct RunStats {
  std::string scene, gi, device;
  uint32_t width = 0, height = 0;
  int frames = 0, warmupFrames = 0;
  std::vector<double> frameMs;
  std::map<std::string, std::vector<double>> gpuStageMs;  // pass name -> per frame
  std::map<std::string, std::vector<double>> cpuStageMs;  // system / CPU step -> per frame
  std::map<std::string, double> scalars;                  // counts and sizes
  std::map<std::string, std::map<std::string, double>> sections;  // extra objects, e.g. "vpl": {...}

  std::string toJson() const;
  std::string table() const;  // human-readable per-stage medians
};

}  // namespace dyngi::sample
