#include "dyngi/engine/render/gpu_timer.h"

namespace dyngi::render {

GpuTimer::GpuTimer(VulkanContext& ctx, uint32_t maxSections) : ctx_(ctx), max_(maxSections) {
  if (!ctx.timestampsSupported()) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = max_ * 2;
  DYNGI_VK(vkCreateQueryPool(ctx.device(), &ci, nullptr, &pool_));
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void GpuTimer::beginFrame(VkCommandBuffer cmd) {
  names_.clear();
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, max_ * 2);
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd, const char* name) {
  if (!pool_ || names_.size() >= max_) return UINT32_MAX;
  uint32_t s = uint32_t(names_.size());
  names_.push_back(name);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, s * 2);
  return s;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t section) {
  if (!pool_ || section == UINT32_MAX) return;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, section * 2 + 1);
}

void GpuTimer::resolve() {
  results_.clear();
  if (!pool_ || names_.empty()) return;
  std::vector<uint64_t> ts(names_.size() * 2);
  VkResult r = vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ts.size()), ts.size() * sizeof(uint64_t), ts.data(),
                                     sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  if (r != VK_SUCCESS) return;
  double toMs = double(ctx_.timestampPeriodNs()) * 1e-6;
  for (size_t i = 0; i < names_.size(); ++i) results_.push_back({names_[i], double(ts[i * 2 + 1] - ts[i * 2]) * toMs});
}

}  // namespace dyngi::render
