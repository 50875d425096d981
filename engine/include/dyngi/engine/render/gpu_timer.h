#pragma once
// Named GPU time sections, read after the frame's fence: from timestamp queries, or (Mode::Fenced) from
// the CPU clock between fences at each section's ends.
#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "dyngi/engine/render/context.h"

namespace dyngi::render {

class GpuTimer {
 public:
  enum class Mode { Timestamps, Fenced };
  GpuTimer(VulkanContext& ctx, Mode mode = Mode::Timestamps, uint32_t maxSections = 64);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Resets the queries this frame uses. Fenced: `fence` submits what was recorded, waits for it and
  // reopens the command buffer (FrameContext::submitAndWait); every section's ends call it.
  void beginFrame(VkCommandBuffer cmd, std::function<void()> fence = {});
  Mode mode() const { return mode_; }
  // Times the frames begun from now on in `mode` (between frames). Timestamps fall back to none on a
  // device without them.
  void setMode(Mode mode);
  uint32_t begin(VkCommandBuffer cmd, const char* name);
  void end(VkCommandBuffer cmd, uint32_t section);
  // Call after the frame's fence has signalled. wait = false: times not yet available are left out
  // instead of waited for (a host's frame, whose fence dyngi does not see).
  void resolve(bool wait = true);
  // (name, milliseconds) of the last resolved frame, in recording order.
  const std::vector<std::pair<std::string, double>>& results() const { return results_; }
  // A fenced frame's sections as the device's timestamps saw them (written beside the fences where the
  // device has timestamps): how much of the fenced time they bracket. Empty for a timestamped frame.
  const std::vector<std::pair<std::string, double>>& timestampResults() const { return timestampResults_; }

 private:
  using Clock = std::chrono::steady_clock;
  VulkanContext& ctx_;
  Mode mode_;
  Mode frameMode_;  // the mode the last frame was begun with (what resolve() reads)
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_;
  std::function<void()> fence_;
  std::vector<std::string> names_;
  std::vector<std::pair<Clock::time_point, Clock::time_point>> cpuTimes_;  // Fenced: per section
  std::vector<std::pair<std::string, double>> results_, timestampResults_;
};

// Debug label + timed section around one pass's commands.
class ScopedPass {
 public:
  ScopedPass(const VulkanContext& ctx, GpuTimer* timer, VkCommandBuffer cmd, const char* name)
      : ctx_(ctx), timer_(timer), cmd_(cmd) {
    // The timer outside the label: a fenced timer's submission never falls inside a label.
    if (timer_) section_ = timer_->begin(cmd, name);
    ctx_.beginLabel(cmd, name);
  }
  ~ScopedPass() {
    ctx_.endLabel(cmd_);
    if (timer_) timer_->end(cmd_, section_);
  }
  ScopedPass(const ScopedPass&) = delete;
  ScopedPass& operator=(const ScopedPass&) = delete;

 private:
  const VulkanContext& ctx_;
  GpuTimer* timer_;
  VkCommandBuffer cmd_;
  uint32_t section_ = 0;
};

}  // namespace dyngi::render
