#pragma once
// Named GPU time sections from timestamp queries, read back after the frame's fence.
#include <string>
#include <utility>
#include <vector>

#include "dyngi/engine/render/context.h"

namespace dyngi::render {

class GpuTimer {
 public:
  GpuTimer(VulkanContext& ctx, uint32_t maxSections = 64);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  void beginFrame(VkCommandBuffer cmd);        // resets the queries this frame uses
  uint32_t begin(VkCommandBuffer cmd, const char* name);
  void end(VkCommandBuffer cmd, uint32_t section);
  void resolve();                              // call after the frame's fence has signalled
  // (name, milliseconds) of the last resolved frame, in recording order.
  const std::vector<std::pair<std::string, double>>& results() const { return results_; }

 private:
  VulkanContext& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_;
  std::vector<std::string> names_;
  std::vector<std::pair<std::string, double>> results_;
};

// Debug label + GPU timestamp around one pass's commands.
class ScopedPass {
 public:
  ScopedPass(const VulkanContext& ctx, GpuTimer* timer, VkCommandBuffer cmd, const char* name)
      : ctx_(ctx), timer_(timer), cmd_(cmd) {
    ctx_.beginLabel(cmd, name);
    if (timer_) section_ = timer_->begin(cmd, name);
  }
  ~ScopedPass() {
    if (timer_) timer_->end(cmd_, section_);
    ctx_.endLabel(cmd_);
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
