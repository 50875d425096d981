#include "dyngi/engine/render/gpu_timer.h"

namespace dyngi::render {

GpuTimer::GpuTimer(VulkanContext& ctx, Mode mode, uint32_t maxSections) : ctx_(ctx), mode_(mode), max_(maxSections) {
  if (mode_ == Mode::Fenced || !ctx.timestampsSupported()) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = max_ * 2;
  DYNGI_VK(vkCreateQueryPool(ctx.device(), &ci, ctx.allocator(), &pool_));
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, ctx_.allocator());
}

void GpuTimer::beginFrame(VkCommandBuffer cmd, std::function<void()> fence) {
  names_.clear();
  cpuTimes_.clear();
  fence_ = mode_ == Mode::Fenced ? std::move(fence) : std::function<void()>();
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, max_ * 2);
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd, const char* name) {
  if ((!pool_ && !fence_) || names_.size() >= max_) return UINT32_MAX;
  uint32_t s = uint32_t(names_.size());
  names_.push_back(name);
  if (fence_) {
    fence_();  // what came before is done: the clock starts on this section alone
    cpuTimes_.push_back({Clock::now(), Clock::now()});
  } else {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, s * 2);
  }
  return s;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t section) {
  if (section == UINT32_MAX) return;
  if (fence_) {
    fence_();
    cpuTimes_[section].second = Clock::now();
  } else if (pool_) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, section * 2 + 1);
  }
}

void GpuTimer::resolve(bool wait) {
  results_.clear();
  if (names_.empty()) return;
  if (mode_ == Mode::Fenced) {
    for (size_t i = 0; i < names_.size(); ++i)
      results_.push_back({names_[i], std::chrono::duration<double, std::milli>(cpuTimes_[i].second - cpuTimes_[i].first).count()});
    return;
  }
  if (!pool_) return;
  std::vector<uint64_t> ts(names_.size() * 2);
  VkResult r = vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ts.size()), ts.size() * sizeof(uint64_t), ts.data(),
                                     sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
  if (r != VK_SUCCESS) return;
  double toMs = double(ctx_.timestampPeriodNs()) * 1e-6;
  for (size_t i = 0; i < names_.size(); ++i) results_.push_back({names_[i], double(ts[i * 2 + 1] - ts[i * 2]) * toMs});
}

}  // namespace dyngi::render
