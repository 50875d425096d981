#include "gi_views.h"

#include "dyngi/engine/render/gpu_timer.h"
#include "shaders/shared/gi_gpu_types.h"
#include "spirv/gi_indirect_view.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

GiIndirectView::GiIndirectView(render::VulkanContext& ctx) : ctx_(ctx) {
  const Binding bindings[] = {{DYNGI_GI_VIEW_BINDING_INDIRECT, kStorageImage, kCS}, {DYNGI_GI_VIEW_BINDING_OUT_HDR, kStorageImage, kCS}};
  pipeline_ = render::LazyPipeline::compute(ctx, DYNGI_SHADER(spv_gi_indirect_view_comp), bindings, 0, "gi_indirect_view");
}

void GiIndirectView::recordAfterLighting(render::FrameContext& frame) {
  if (!enabled) return;
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "indirect_view");
  render::RenderTargets& t = frame.targets;
  t.indirect.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  t.hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get().handle());
  DescriptorWrites()
      .storageImage(DYNGI_GI_VIEW_BINDING_INDIRECT, t.indirect.view())
      .storageImage(DYNGI_GI_VIEW_BINDING_OUT_HDR, t.hdr.view())
      .push(ctx_, frame.cmd, pipeline_.get());
  vkCmdDispatch(frame.cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

}  // namespace dyngi::gi
