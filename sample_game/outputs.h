#pragma once
// What a run leaves behind: the PNG, the EXR, the stats JSON and table, the memory log. Each writer
// prints "wrote FILE" or one error line and returns the exit status it adds (0 or 1).
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "dyngi/engine/platform/files.h"
#include "dyngi/engine/render/context.h"
#include "dyngi/engine/render/image_metrics.h"
#include "options.h"
#include "stats.h"

namespace dyngi::sample {

// --out (tone-mapped sRGB) and --hdr-out (linear radiance) of one frame; each image is made (read back)
// only when its file was asked for.
int writeImages(const Options& o, uint32_t width, uint32_t height, const std::function<std::vector<uint8_t>()>& ldr,
                const std::function<render::ImageRgba()>& hdr);
// --stats, then the table on stdout.
int writeStats(const Options& o, const RunStats& stats);

// Options as the stats' "settings" report them, by flag name: a number (bools 0 or 1), or a choice's name.
void addSettings(RunStats& stats, const std::vector<gi::OptionRef>& options);

// The stats' "memory" object: device memory allocated now and at its peak, and the process's peak
// resident memory (on an integrated device or lavapipe the device memory is part of the latter).
void addMemory(RunStats& stats, const render::VulkanContext& ctx);

// --memory-log: every kEvery rendered frames, resident memory and live Vulkan allocations.
class MemoryLog {
 public:
  static constexpr int kEvery = 100;
  // False (with the error line printed) when the file cannot be opened; no log without --memory-log.
  bool open(const std::string& path);
  void frameRendered(int rendered, const render::VulkanContext& ctx);
  // "wrote FILE", or the first failed write or close as one error line; returns the exit status it adds.
  int close();

 private:
  platform::OutputStream file_;
  std::string path_;
};

}  // namespace dyngi::sample
