#include "techniques/many_lights/indirect_passes.h"

#include <algorithm>

#include "spirv/filter.comp.spv.h"
#include "spirv/gather.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

IndirectGatherPass::IndirectGatherPass(render::VulkanContext& ctx, bool accumulate) : ctx_(ctx), accumulate_(accumulate) {
  if (!ctx.enabledFeatures().shaderStorageImageExtendedFormats)
    throw render::VulkanError("the indirect gather needs shaderStorageImageExtendedFormats (rg32ui storage images); " + ctx.deviceName() +
                              " does not support it");
  const Binding b[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                       {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},         {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kCS},
                       {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kCS},         {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                       {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kCS},         {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                       {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},          {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kCS},
                       {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kCS}};
  const uint32_t spec[] = {accumulate ? 1u : 0u};
  pipeline_ = render::Pipeline::compute(ctx, DYNGI_SHADER(spv_gather_comp), b, sizeof(gpu::GatherPush) + sizeof(gpu::AccumulatePush),
                                        accumulate ? "indirect_gather_accumulate" : "indirect_gather", spec);
  if (!accumulate) {
    // The temporal images' bindings must hold images of their declared kind even when never used.
    auto unused = [&](VkFormat f, VkImageViewType type, const char* name) {
      render::ImageDesc d;
      d.format = f;
      d.layers = type == VK_IMAGE_VIEW_TYPE_2D_ARRAY ? 2 : 1;
      d.viewType = type;
      d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
      d.name = name;
      return render::Image(ctx, d);
    };
    unusedSetSamples_ = unused(VK_FORMAT_R32G32_UINT, VK_IMAGE_VIEW_TYPE_2D_ARRAY, "unused set samples");
    unusedSums_ = unused(VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_VIEW_TYPE_2D, "unused sums");
  }
}

void IndirectGatherPass::record(render::FrameContext& frame, VkBuffer vpls, VkBuffer nodes, VkBuffer bits, render::Image& raw,
                                const gpu::GatherPush& pc, const TemporalBuffers* temporal) {
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "indirect");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  for (render::Image* in : {&t.position, &t.normal})
    in->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  raw.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // The shader declares stores to these bindings (taken only when accumulating): the barrier must cover
  // writes too, or synchronization validation sees a write after the layout transition.
  for (render::Image* unused : {&unusedSetSamples_, &unusedSums_})
    if (unused->valid() && unused->layout() != VK_IMAGE_LAYOUT_GENERAL)
      unused->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
  const bool acc = accumulate_ && temporal;
  // Without accumulation the temporal bindings are never read; any valid buffer keeps them defined.
  DescriptorWrites()
      .uniformBuffer(0, frame.frameUniforms.handle())
      .storageImage(1, t.position.view())
      .storageImage(2, t.normal.view())
      .storageBuffer(3, vpls)
      .storageBuffer(4, nodes)
      .storageImage(5, raw.view())
      .storageBuffer(6, bits)
      .storageImage(7, acc ? temporal->setSamples : unusedSetSamples_.view())
      .storageImage(8, acc ? temporal->sums : unusedSums_.view())
      .storageBuffer(9, acc ? temporal->queue : vpls)
      .storageBuffer(10, acc ? temporal->queueArgs : vpls)
      .push(ctx_, cmd, pipeline_);
  vkCmdPushConstants(cmd, pipeline_.layout(), kCS, 0, sizeof(pc), &pc);
  if (acc) vkCmdPushConstants(cmd, pipeline_.layout(), kCS, sizeof(pc), sizeof(temporal->push), &temporal->push);
  const uint32_t K = pc.info.y;
  vkCmdDispatch(cmd, dispatchGroups(dispatchGroups(t.width, K), 8), dispatchGroups(dispatchGroups(t.height, K), 8), K * K);
}

IndirectFilterPass::IndirectFilterPass(render::VulkanContext& ctx) : ctx_(ctx) {}

void IndirectFilterPass::record(render::FrameContext& frame, render::Image& input, uint32_t K, float planeTolerance) {
  K = std::clamp(K, 1u, 8u);
  render::Pipeline& pipeline = pipelines_[K - 1];
  if (!pipeline.handle()) {
    const Binding b[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                         {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                         {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS}};
    const uint32_t spec[] = {K};
    pipeline = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_filter_comp), b, sizeof(gpu::IndirectFilterPush), "indirect_filter", spec);
  }
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "filter");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  input.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  t.indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  DescriptorWrites()
      .uniformBuffer(0, frame.frameUniforms.handle())
      .storageImage(1, input.view())
      .storageImage(2, t.indirect.view())
      .push(ctx_, cmd, pipeline);
  const gpu::IndirectFilterPush pc{planeTolerance};
  vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

}  // namespace dyngi::gi
