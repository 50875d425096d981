// The full-screen compute passes: lighting and tone mapping.
#include "shared/gpu_types.h"
#include "passes.h"
#include "spirv/lighting.comp.spv.h"
#include "spirv/tonemap.comp.spv.h"

namespace dyngi::render {
namespace {
constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageWrite = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkAccessFlags2 kRead = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;

void prepareOutput(VkCommandBuffer cmd, Image& img) { img.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, kCompute, kStorageWrite); }
void prepareInput(VkCommandBuffer cmd, Image& img) { img.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, kCompute, kRead); }
}  // namespace

LightingPass::LightingPass(VulkanContext& ctx) : ctx_(ctx) {
  const Binding b[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {9, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
  pipeline_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_lighting_comp), b, sizeof(gpu::LightingPush), "lighting");
}

void LightingPass::execute(FrameContext& frame, ShadowPass& shadows, bool hasIndirect) {
  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  RenderTargets& t = frame.targets;
  for (Image* in : {&t.position, &t.normal, &t.albedo, &t.emissive, &t.indirect}) prepareInput(cmd, *in);
  prepareOutput(cmd, t.hdr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
  DescriptorWrites()
      .uniformBuffer(0, frame.frameUniforms.handle())
      .storageImage(1, t.position.view())
      .storageImage(2, t.normal.view())
      .storageImage(3, t.albedo.view())
      .storageImage(4, t.emissive.view())
      .storageBuffer(5, shadows.lights().handle())
      .storageBuffer(6, shadows.matrices().handle())
      .storageImage(7, shadows.shadowMap().view())
      .storageImage(8, t.indirect.view())
      .storageImage(9, t.hdr.view())
      .push(ctx_, cmd, pipeline_);
  const gpu::LightingPush pc{hasIndirect ? 1u : 0u};
  vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

TonemapPass::TonemapPass(VulkanContext& ctx) : ctx_(ctx) {
  const Binding b[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
  pipeline_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_tonemap_comp), b, 0, "tonemap");
}

void TonemapPass::execute(FrameContext& frame) {
  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  RenderTargets& t = frame.targets;
  prepareInput(cmd, t.hdr);
  prepareOutput(cmd, t.ldr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.handle());
  DescriptorWrites()
      .uniformBuffer(0, frame.frameUniforms.handle())
      .storageImage(1, t.hdr.view())
      .storageImage(2, t.ldr.view())
      .push(ctx_, cmd, pipeline_);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

}  // namespace dyngi::render
