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
  const Binding b[] = {{DYNGI_LIGHTING_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_G_POSITION, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_G_NORMAL, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_G_ALBEDO, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_G_EMISSIVE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_SHADOW_MATRICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_SHADOW_MAPS, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_INDIRECT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_OUT_HDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_LIGHTING_BINDING_SPECULAR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
  static_assert(uint32_t(SpecularSource::None) == 0 && uint32_t(SpecularSource::Target) == 1 && uint32_t(SpecularSource::Indirect) == 2,
                "lighting.comp's kSpecular");
  for (uint32_t specular : {0u, 1u, 2u}) {
    const uint32_t spec[] = {specular};
    pipeline_[specular] = Pipeline::compute(ctx, DYNGI_SHADER(spv_lighting_comp), b, sizeof(gpu::LightingPush), "lighting", spec);
  }
}

void LightingPass::execute(FrameContext& frame, ShadowPass& shadows, bool hasIndirect, SpecularSource specular) {
  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  RenderTargets& t = frame.targets;
  for (Image* in : {&t.position, &t.normal, &t.albedo, &t.emissive, &t.indirect, &t.specular}) prepareInput(cmd, *in);
  prepareOutput(cmd, t.hdr);
  const Pipeline& pipeline = pipeline_[uint32_t(specular)];
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_LIGHTING_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_LIGHTING_BINDING_G_POSITION, t.position.view())
      .storageImage(DYNGI_LIGHTING_BINDING_G_NORMAL, t.normal.view())
      .storageImage(DYNGI_LIGHTING_BINDING_G_ALBEDO, t.albedo.view())
      .storageImage(DYNGI_LIGHTING_BINDING_G_EMISSIVE, t.emissive.view())
      .storageBuffer(DYNGI_LIGHTING_BINDING_LIGHTS, shadows.lights().handle())
      .storageBuffer(DYNGI_LIGHTING_BINDING_SHADOW_MATRICES, shadows.matrices().handle())
      .storageImage(DYNGI_LIGHTING_BINDING_SHADOW_MAPS, shadows.shadowMap().view())
      .storageImage(DYNGI_LIGHTING_BINDING_INDIRECT, t.indirect.view())
      .storageImage(DYNGI_LIGHTING_BINDING_OUT_HDR, t.hdr.view())
      .storageImage(DYNGI_LIGHTING_BINDING_SPECULAR, t.specular.view())
      .push(ctx_, cmd, pipeline);
  const gpu::LightingPush pc{hasIndirect ? 1u : 0u};
  vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

TonemapPass::TonemapPass(VulkanContext& ctx) : ctx_(ctx) {
  const Binding b[] = {{DYNGI_TONEMAP_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_TONEMAP_BINDING_HDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT},
                       {DYNGI_TONEMAP_BINDING_LDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
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
      .uniformBuffer(DYNGI_TONEMAP_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_TONEMAP_BINDING_HDR, t.hdr.view())
      .storageImage(DYNGI_TONEMAP_BINDING_LDR, t.ldr.view())
      .push(ctx_, cmd, pipeline_);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
}

}  // namespace dyngi::render
