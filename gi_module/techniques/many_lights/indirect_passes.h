#pragma once
// The two passes both VPL techniques share: the interleaved gather (gather.comp) and the
// geometry-aware merge filter (filter.comp).
#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"
#include "shaders/shared/gi_gpu_types.h"

namespace dyngi::gi {

class IndirectGatherPass {
 public:
  // With `accumulate` (the temporal technique) each pixel's light is accumulated into the temporal sets
  // right away (temporal_accumulate.glsl) and `raw` receives the accumulated light.
  IndirectGatherPass(render::VulkanContext& ctx, bool accumulate = false);
  // The temporal technique's buffers (accumulate only).
  struct TemporalBuffers {
    VkImageView setSamples = VK_NULL_HANDLE, sums = VK_NULL_HANDLE;  // storage images, in GENERAL layout
    VkBuffer queue = VK_NULL_HANDLE, queueArgs = VK_NULL_HANDLE;  // pixels queued for the full reprojection
    gpu::AccumulatePush push{};
  };
  // Gathers `vpls` into `raw` (rgba32ui, filter_input.glsl's packing; "indirect" in stats). `nodes` is the
  // SVO (visibility 0), `bits` the precomputed visibility (visibility 2); pass any valid buffer when unused.
  void record(render::FrameContext& frame, VkBuffer vpls, VkBuffer nodes, VkBuffer bits, render::Image& raw, const gpu::GatherPush& pc,
              const TemporalBuffers* temporal = nullptr);

 private:
  render::VulkanContext& ctx_;
  render::Pipeline pipeline_;
  bool accumulate_ = false;
  render::Image unusedSetSamples_, unusedSums_;  // bound in place of the temporal images without accumulation
};

class IndirectFilterPass {
 public:
  explicit IndirectFilterPass(render::VulkanContext& ctx);
  // Filters `input` (interleaved K x K, K in 1..8; rgba32ui packed as in filter_input.glsl) into
  // frame.targets.indirect ("filter" in stats).
  void record(render::FrameContext& frame, render::Image& input, uint32_t K, float planeTolerance);

 private:
  render::VulkanContext& ctx_;
  render::Pipeline pipelines_[8];  // per K, made on first use: K is a specialization constant
};

}  // namespace dyngi::gi
