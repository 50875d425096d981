#include "indirect/indirect_passes.h"

#include <algorithm>
#include <vector>

#include "spirv/filter_columns.comp.spv.h"
#include "spirv/filter_rows.comp.spv.h"
#include "spirv/gather.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

namespace {
// The shared gather's bindings (gather.glsl).
std::vector<Binding> gatherBindings(std::span<const Binding> extra) {
  std::vector<Binding> b = {{DYNGI_GATHER_BINDING_FRAME, kUBO, kCS},         {DYNGI_GATHER_BINDING_POSITION, kStorageImage, kCS},
                            {DYNGI_GATHER_BINDING_NORMAL, kStorageImage, kCS}, {DYNGI_GATHER_BINDING_VPLS, kSSBO, kCS},
                            {DYNGI_GATHER_BINDING_SVO_NODES, kSSBO, kCS},      {DYNGI_GATHER_BINDING_OUTPUT, kStorageImage, kCS},
                            {DYNGI_GATHER_BINDING_VISIBILITY_BITS, kSSBO, kCS}};
  b.insert(b.end(), extra.begin(), extra.end());
  return b;
}
}  // namespace

IndirectGatherPass::IndirectGatherPass(render::VulkanContext& ctx)
    : IndirectGatherPass(ctx, DYNGI_SHADER(spv_gather_comp), {}, 0, "indirect_gather") {}

IndirectGatherPass::IndirectGatherPass(render::VulkanContext& ctx, render::ShaderCode variant, std::span<const Binding> extraBindings,
                                       uint32_t extraPushBytes, const char* name)
    : ctx_(ctx), extraPushBytes_(extraPushBytes) {
  if (!ctx.enabledFeatures().shaderStorageImageExtendedFormats)
    throw render::VulkanError("the indirect gather needs shaderStorageImageExtendedFormats (rg32ui storage images); " + ctx.deviceName() +
                              " does not support it");
  const std::vector<Binding> b = gatherBindings(extraBindings);
  pipeline_ = render::Pipeline::compute(ctx, variant, b, sizeof(gpu::GatherPush) + extraPushBytes, name);
}

void IndirectGatherPass::record(render::FrameContext& frame, render::Image& raw, const Inputs& in) {
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "indirect");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  for (render::Image* img : {&t.position, &t.normal})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  raw.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
  DescriptorWrites writes;
  writes.uniformBuffer(DYNGI_GATHER_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_GATHER_BINDING_POSITION, t.position.view())
      .storageImage(DYNGI_GATHER_BINDING_NORMAL, t.normal.view())
      .storageBuffer(DYNGI_GATHER_BINDING_VPLS, in.vpls)
      .storageBuffer(DYNGI_GATHER_BINDING_SVO_NODES, in.nodes)
      .storageImage(DYNGI_GATHER_BINDING_OUTPUT, raw.view())
      .storageBuffer(DYNGI_GATHER_BINDING_VISIBILITY_BITS, in.bits);
  if (in.extraWrites) in.extraWrites(writes);
  writes.push(ctx_, cmd, pipeline_);
  vkCmdPushConstants(cmd, pipeline_.layout(), kCS, 0, sizeof(in.push), &in.push);
  if (extraPushBytes_ > 0 && in.extraPush)
    vkCmdPushConstants(cmd, pipeline_.layout(), kCS, sizeof(in.push), extraPushBytes_, in.extraPush);
  const uint32_t K = in.push.interleave;
  vkCmdDispatch(cmd, dispatchGroups(dispatchGroups(t.width, K), 8), dispatchGroups(dispatchGroups(t.height, K), 8), K * K);
}

IndirectFilterPass::IndirectFilterPass(render::VulkanContext& ctx) : ctx_(ctx) {}

void IndirectFilterPass::record(render::FrameContext& frame, render::Image& input, uint32_t K, float planeTolerance) {
  K = std::clamp(K, 1u, 8u);
  const uint32_t spec[] = {K};
  render::Pipeline& rows = rows_[K - 1];
  if (!rows.handle()) {
    const Binding b[] = {{DYNGI_FILTER_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                         {DYNGI_FILTER_BINDING_FILTER_INPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                         {DYNGI_FILTER_BINDING_OUT_ROWS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS}};
    rows = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_filter_rows_comp), b, sizeof(gpu::IndirectFilterPush), "indirect_filter_rows", spec);
  }
  render::Pipeline& columns = columns_[K - 1];
  if (!columns.handle()) {
    const Binding b[] = {{DYNGI_FILTER_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                         {DYNGI_FILTER_BINDING_FILTER_INPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                         {DYNGI_FILTER_BINDING_OUT_INDIRECT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS}};
    columns = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_filter_columns_comp), b, sizeof(gpu::IndirectFilterPush),
                                        "indirect_filter_columns", spec);
  }
  render::RenderTargets& t = frame.targets;
  if (!rowsResult_.valid() || rowsResult_.desc().width != t.width || rowsResult_.desc().height != t.height) {
    render::ImageDesc d;
    d.width = t.width;
    d.height = t.height;
    d.format = VK_FORMAT_R32G32B32A32_UINT;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    d.name = "indirect filter rows";
    rowsResult_ = render::Image(ctx_, d);
  }
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "filter");
  VkCommandBuffer cmd = frame.cmd;
  const gpu::IndirectFilterPush pc{planeTolerance};
  input.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  rowsResult_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, rows.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_FILTER_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_FILTER_BINDING_FILTER_INPUT, input.view())
      .storageImage(DYNGI_FILTER_BINDING_OUT_ROWS, rowsResult_.view())
      .push(ctx_, cmd, rows);
  vkCmdPushConstants(cmd, rows.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
  rowsResult_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  t.indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, columns.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_FILTER_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_FILTER_BINDING_FILTER_INPUT, rowsResult_.view())
      .storageImage(DYNGI_FILTER_BINDING_OUT_INDIRECT, t.indirect.view())
      .push(ctx_, cmd, columns);
  vkCmdPushConstants(cmd, columns.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

}  // namespace dyngi::gi
