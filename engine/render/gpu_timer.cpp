#include "dyngi/engine/render/gpu_timer.h"

namespace dyngi::render {

GpuTimer::GpuTimer(VulkanContext& ctx, Mode mode, uint32_t maxSections) : ctx_(ctx), mode_(mode), frameMode_(mode), max_(maxSections) {
  setMode(mode);
}

void GpuTimer::setMode(Mode mode) {
  mode_ = mode;
  if (mode_ == Mode::Fenced || pool_ || !ctx_.timestampsSupported()) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = max_ * 2;
  DYNGI_VK(vkCreateQueryPool(ctx_.device(), &ci, ctx_.allocator(), &pool_));
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, ctx_.allocator());
}

void GpuTimer::beginFrame(VkCommandBuffer cmd, std::function<void()> fence) {
  names_.clear();
  cpuTimes_.clear();
  frameMode_ = mode_;
  fence_ = mode_ == Mode::Fenced ? std::move(fence) : std::function<void()>();
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, max_ * 2);
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd, const char* name) {
  if ((frameMode_ == Mode::Timestamps ? !pool_ : !fence_) || names_.size() >= max_) return UINT32_MAX;
  uint32_t s = uint32_t(names_.size());
  names_.push_back(name);
  if (fence_) {
    fence_();  // what came before is done: the clock starts on this section alone
    cpuTimes_.push_back({Clock::now(), Clock::now()});
  }
  if (pool_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, s * 2);
  return s;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t section) {
  if (section == UINT32_MAX) return;
  if (pool_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, section * 2 + 1);
  if (fence_) {
    fence_();
    cpuTimes_[section].second = Clock::now();
  }
}

void GpuTimer::resolve(bool wait) {
  results_.clear();
  timestampResults_.clear();
  if (names_.empty()) return;
  std::vector<std::pair<std::string, double>> stamped;
  if (pool_) {
    std::vector<uint64_t> ts(names_.size() * 2);
    VkResult r = vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ts.size()), ts.size() * sizeof(uint64_t), ts.data(), sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
    const double toMs = double(ctx_.timestampPeriodNs()) * 1e-6;
    if (r == VK_SUCCESS)
      for (size_t i = 0; i < names_.size(); ++i) stamped.push_back({names_[i], double(ts[i * 2 + 1] - ts[i * 2]) * toMs});
  }
  if (frameMode_ == Mode::Fenced) {
    for (size_t i = 0; i < names_.size(); ++i)
      results_.push_back({names_[i], std::chrono::duration<double, std::milli>(cpuTimes_[i].second - cpuTimes_[i].first).count()});
    timestampResults_ = std::move(stamped);
  } else {
    results_ = std::move(stamped);
  }
}

}  // namespace dyngi::render
