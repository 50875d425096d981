#include "voxel/voxel_debug_pass.h"

#include "dyngi/engine/render/gpu_timer.h"
#include "voxel/shaders/voxel_shared.h"
#include "spirv/voxel_debug.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

VoxelDebugPass::VoxelDebugPass(render::VulkanContext& ctx) : ctx_(ctx) {
  const Binding debugB[] = {{DYNGI_VOXEL_DEBUG_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_NODES, kSSBO, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_NODE_CELLS, kSSBO, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS}};
  pipeline_ = render::LazyPipeline::compute(ctx, DYNGI_SHADER(spv_voxel_debug_comp), debugB, sizeof(gpu::VoxelDebugPush), "voxel_debug");
}

void VoxelDebugPass::record(render::FrameContext& frame, const VoxelScene& voxels, VoxelDebugView view) {
  const VoxelVolume& volume = voxels.volume();
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "voxel_debug_view");
  render::RenderTargets& t = frame.targets;
  t.hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get().handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VOXEL_DEBUG_BINDING_FRAME, frame.frameUniforms.handle())
      .storageBuffer(DYNGI_VOXEL_DEBUG_BINDING_NODES, voxels.nodes().handle())
      .storageBuffer(DYNGI_VOXEL_DEBUG_BINDING_NODE_CELLS, voxels.nodeCells().handle())
      .storageImage(DYNGI_VOXEL_DEBUG_BINDING_VOXEL_ATTRIBUTES, voxels.voxelAttributes().view())
      .storageImage(DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR, t.hdr.view())
      .push(ctx_, frame.cmd, pipeline_.get());
  const gpu::VoxelDebugPush pc{glm::vec4(volume.origin, 1.0f / volume.voxelSize), volume.depth(), float(volume.resolution),
                               view == VoxelDebugView::SvoSteps ? 1u : 0u};
  vkCmdPushConstants(frame.cmd, pipeline_.get().layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(frame.cmd, (t.width + 7) / 8, (t.height + 7) / 8, 1);
}

}  // namespace dyngi::gi
