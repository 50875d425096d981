#include "indirect/indirect_passes.h"

#include <algorithm>
#include <vector>

#include "dyngi/gi/vpl_options.h"
#include "indirect/clamp_spread.h"
#include "spirv/compensate.comp.spv.h"
#include "spirv/compensate_blur.comp.spv.h"
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
                            {DYNGI_GATHER_BINDING_VISIBILITY_BITS, kSSBO, kCS}, {DYNGI_GATHER_BINDING_CLAMP_SPREAD, kSSBO, kCS}};
  b.insert(b.end(), extra.begin(), extra.end());
  return b;
}
}  // namespace

IndirectGatherPass::IndirectGatherPass(render::VulkanContext& ctx)
    : IndirectGatherPass(ctx, DYNGI_SHADER(spv_gather_comp), {}, 0, "indirect_gather") {}

IndirectGatherPass::IndirectGatherPass(render::VulkanContext& ctx, render::ShaderCode variant, std::span<const Binding> extraBindings,
                                       uint32_t extraPushBytes, const char* name)
    : ctx_(ctx), variant_(variant), bindings_(gatherBindings(extraBindings)), name_(name), extraPushBytes_(extraPushBytes) {
  if (!ctx.enabledFeatures().shaderStorageImageExtendedFormats)
    throw render::VulkanError("the indirect gather needs shaderStorageImageExtendedFormats (rg32ui storage images); " + ctx.deviceName() +
                              " does not support it");
  pipeline_ = render::Pipeline::compute(ctx, variant, bindings_, sizeof(gpu::GatherPush) + extraPushBytes, name);
  const std::vector<glm::vec2>& table = clampSpreadTable();
  clampSpread_ = render::Buffer(ctx, table.size() * sizeof(glm::vec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, render::MemoryUsage::Upload,
                                "clamp spread table");
  clampSpread_.upload(table.data(), table.size() * sizeof(glm::vec2));
}

void IndirectGatherPass::record(render::FrameContext& frame, render::Image& raw, const Inputs& in) {
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "indirect");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  for (render::Image* img : {&t.position, &t.normal})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  raw.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // At most DYNGI_GATHER_MAX_VPLS_PER_PIXEL VPLs a pixel per dispatch (why: at the define). A gather
  // within it, as with the defaults, is one dispatch of the plain pipeline.
  const uint32_t K = in.push.interleave, chunk = DYNGI_GATHER_MAX_VPLS_PER_PIXEL * K * K;
  const bool chunked = in.push.vplCount > chunk;
  if (chunked && !chunked_.handle()) {
    const uint32_t spec[] = {1u};  // kGatherChunked
    chunked_ = render::Pipeline::compute(ctx_, variant_, bindings_, sizeof(gpu::GatherPush) + extraPushBytes_, name_, spec);
  }
  render::Pipeline& pipeline = chunked ? chunked_ : pipeline_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  DescriptorWrites writes;
  writes.uniformBuffer(DYNGI_GATHER_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_GATHER_BINDING_POSITION, t.position.view())
      .storageImage(DYNGI_GATHER_BINDING_NORMAL, t.normal.view())
      .storageBuffer(DYNGI_GATHER_BINDING_VPLS, in.vpls)
      .storageBuffer(DYNGI_GATHER_BINDING_SVO_NODES, in.nodes)
      .storageImage(DYNGI_GATHER_BINDING_OUTPUT, raw.view())
      .storageBuffer(DYNGI_GATHER_BINDING_VISIBILITY_BITS, in.bits)
      .storageBuffer(DYNGI_GATHER_BINDING_CLAMP_SPREAD, clampSpread_.handle());
  if (in.extraWrites) in.extraWrites(writes);
  writes.push(ctx_, cmd, pipeline);
  if (extraPushBytes_ > 0 && in.extraPush)
    vkCmdPushConstants(cmd, pipeline.layout(), kCS, sizeof(in.push), extraPushBytes_, in.extraPush);
  gpu::GatherPush push = in.push;
  for (push.chunkBegin = 0;; push.chunkBegin += chunk) {
    push.chunkEnd = std::min(push.vplCount, push.chunkBegin + chunk);
    vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, dispatchGroups(dispatchGroups(t.width, K), 8), dispatchGroups(dispatchGroups(t.height, K), 8), K * K);
    if (push.chunkEnd >= push.vplCount) break;
    raw.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
}

IndirectFilterPass::IndirectFilterPass(render::VulkanContext& ctx) : ctx_(ctx) {}

bool IndirectFilterPass::compensates(const VplOptions& vpl) { return vpl.clampCompensation > 0 && vpl.distanceClamp > 0.0f; }

void IndirectFilterPass::record(render::FrameContext& frame, render::Image& input, uint32_t K, const VplOptions& vpl) {
  K = std::clamp(K, 1u, 8u);
  const bool compensate = compensates(vpl);
  const uint32_t spec[] = {K, compensate ? 1u : 0u};
  render::Pipeline& rows = rows_[K - 1];
  if (!rows.handle()) {
    const Binding b[] = {{DYNGI_FILTER_BINDING_FRAME, kUBO, kCS},
                         {DYNGI_FILTER_BINDING_FILTER_INPUT, kStorageImage, kCS},
                         {DYNGI_FILTER_BINDING_OUT_ROWS, kStorageImage, kCS}};
    rows = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_filter_rows_comp), std::span(b), sizeof(gpu::IndirectFilterPush),
                                     "indirect_filter_rows", std::span(spec, 1));
  }
  render::Pipeline& columns = columns_[K - 1][compensate ? 1 : 0];
  if (!columns.handle()) {
    const Binding b[] = {{DYNGI_FILTER_BINDING_FRAME, kUBO, kCS},
                         {DYNGI_FILTER_BINDING_FILTER_INPUT, kStorageImage, kCS},
                         {DYNGI_FILTER_BINDING_OUT_INDIRECT, kStorageImage, kCS},
                         {DYNGI_FILTER_BINDING_COMPENSATION, kStorageImage, kCS}};
    columns = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_filter_columns_comp), b, sizeof(gpu::IndirectFilterPush),
                                        "indirect_filter_columns", spec);
  }
  render::RenderTargets& t = frame.targets;
  auto screenImage = [&](render::Image& img, uint32_t width, uint32_t height, const char* name) {
    if (img.valid() && img.desc().width == width && img.desc().height == height) return;
    render::ImageDesc d;
    d.width = width;
    d.height = height;
    d.format = VK_FORMAT_R32G32B32A32_UINT;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    d.name = name;
    img = render::Image(ctx_, d);
  };
  screenImage(rowsResult_, t.width, t.height, "indirect filter rows");
  constexpr uint32_t S = DYNGI_COMPENSATE_SCALE;
  screenImage(compensation_, (t.width + S - 1) / S, (t.height + S - 1) / S, "clamp compensation");  // bound by both variants
  if (compensate) screenImage(traced_, (t.width + S - 1) / S, (t.height + S - 1) / S, "clamp compensation traced");
  VkCommandBuffer cmd = frame.cmd;
  const gpu::IndirectFilterPush pc{vpl.filterPlaneTolerance};
  {
    render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "filter");
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
  }
  if (compensate) recordCompensation(frame, vpl);
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "filter");
  compensation_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  t.indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, columns.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_FILTER_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_FILTER_BINDING_FILTER_INPUT, rowsResult_.view())
      .storageImage(DYNGI_FILTER_BINDING_OUT_INDIRECT, t.indirect.view())
      .storageImage(DYNGI_FILTER_BINDING_COMPENSATION, compensation_.view())
      .push(ctx_, cmd, columns);
  vkCmdPushConstants(cmd, columns.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

void IndirectFilterPass::recordCompensation(render::FrameContext& frame, const VplOptions& vpl) {
  if (!compensate_.handle()) {
    const Binding b[] = {{DYNGI_COMPENSATE_BINDING_FRAME, kUBO, kCS},           {DYNGI_COMPENSATE_BINDING_POSITION, kStorageImage, kCS},
                         {DYNGI_COMPENSATE_BINDING_NORMAL, kStorageImage, kCS},   {DYNGI_COMPENSATE_BINDING_ALBEDO, kStorageImage, kCS},
                         {DYNGI_COMPENSATE_BINDING_EMISSIVE, kStorageImage, kCS}, {DYNGI_COMPENSATE_BINDING_ROWS, kStorageImage, kCS},
                         {DYNGI_COMPENSATE_BINDING_LIGHTS, kSSBO, kCS},           {DYNGI_COMPENSATE_BINDING_SHADOW_MATRICES, kSSBO, kCS},
                         {DYNGI_COMPENSATE_BINDING_SHADOW_MAPS, kStorageImage, kCS}, {DYNGI_COMPENSATE_BINDING_OUT, kStorageImage, kCS}};
    compensate_ = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_compensate_comp), b, sizeof(gpu::CompensatePush), "compensate");
    const Binding blur[] = {{DYNGI_COMPENSATE_BINDING_FRAME, kUBO, kCS},
                            {DYNGI_COMPENSATE_BINDING_TRACED, kStorageImage, kCS},
                            {DYNGI_COMPENSATE_BINDING_OUT, kStorageImage, kCS}};
    compensateBlur_ = render::Pipeline::compute(ctx_, DYNGI_SHADER(spv_compensate_blur_comp), blur, sizeof(gpu::CompensatePush), "compensate_blur");
  }
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "compensate");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  const render::LightInputs& lights = frame.lights;
  for (render::Image* img : {&t.position, &t.normal, &t.albedo, &t.emissive, lights.shadowMaps})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  traced_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compensate_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_COMPENSATE_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_COMPENSATE_BINDING_POSITION, t.position.view())
      .storageImage(DYNGI_COMPENSATE_BINDING_NORMAL, t.normal.view())
      .storageImage(DYNGI_COMPENSATE_BINDING_ALBEDO, t.albedo.view())
      .storageImage(DYNGI_COMPENSATE_BINDING_EMISSIVE, t.emissive.view())
      .storageImage(DYNGI_COMPENSATE_BINDING_ROWS, rowsResult_.view())
      .storageBuffer(DYNGI_COMPENSATE_BINDING_LIGHTS, lights.lights->handle())
      .storageBuffer(DYNGI_COMPENSATE_BINDING_SHADOW_MATRICES, lights.shadowMatrices->handle())
      .storageImage(DYNGI_COMPENSATE_BINDING_SHADOW_MAPS, lights.shadowMaps->view())
      .storageImage(DYNGI_COMPENSATE_BINDING_OUT, traced_.view())
      .push(ctx_, cmd, compensate_);
  const gpu::CompensatePush pc{vpl.distanceClamp, vpl.clampCompensation, (vpl.bounces > 1 || vpl.bounceTail) ? 1u : 0u, lights.count,
                               vpl.filterPlaneTolerance};
  vkCmdPushConstants(cmd, compensate_.layout(), kCS, 0, sizeof(pc), &pc);
  const uint32_t groupsX = dispatchGroups(traced_.desc().width, 8), groupsY = dispatchGroups(traced_.desc().height, 8);
  vkCmdDispatch(cmd, groupsX, groupsY, 1);
  traced_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  compensation_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compensateBlur_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_COMPENSATE_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_COMPENSATE_BINDING_TRACED, traced_.view())
      .storageImage(DYNGI_COMPENSATE_BINDING_OUT, compensation_.view())
      .push(ctx_, cmd, compensateBlur_);
  vkCmdPushConstants(cmd, compensateBlur_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, groupsX, groupsY, 1);
}

std::vector<QualityKnob> tailStrideKnob(const VplOptions& vpl, std::function<void(uint32_t)> setStride) {
  if (!vpl.bounceTail) return {};
  const uint32_t from = std::clamp(vpl.bounceTailStride, 1u, 4u), to = std::min(4u, 2u * from);
  std::vector<double> levels = {double(from)};
  if (to > from) levels.push_back(double(to));
  return {{"tail_stride", levels, [set = std::move(setStride)](double v) { set(uint32_t(v)); }}};
}

}  // namespace dyngi::gi
