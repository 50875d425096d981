#include "dyngi/engine/render/draw_pass.h"
#include "shared/gpu_types.h"
#include "passes.h"
#include "spirv/gbuffer.frag.spv.h"
#include "spirv/gbuffer.vert.spv.h"
#include "spirv/gbuffer_tangent.vert.spv.h"

namespace dyngi::render {

GBufferPass::GBufferPass(VulkanContext& ctx) : ctx_(ctx) {}

Pipeline& GBufferPass::pipelineFor(uint32_t textureBits) {
  Pipeline& pipeline = pipelines_[textureBits & 63u];
  if (pipeline.handle()) return pipeline;
  Pipeline::GraphicsDesc d;
  const bool tangents = textureBits & DYNGI_MATERIAL_NORMAL_TEX;
  d.vertex = tangents ? DYNGI_SHADER(spv_gbuffer_tangent_vert) : DYNGI_SHADER(spv_gbuffer_vert);
  d.fragment = DYNGI_SHADER(spv_gbuffer_frag);
  setMeshVertexInput(d, /*normal=*/true, /*uv=*/true);
  if (tangents) setMeshTangentInput(d);
  d.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM,
                    VK_FORMAT_R16G16B16A16_SFLOAT};
  d.depthFormat = VK_FORMAT_D32_SFLOAT;
  d.bindings = {{DYNGI_GBUFFER_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_GBUFFER_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT},
                {DYNGI_GBUFFER_BINDING_BASE_COLOR_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_GBUFFER_BINDING_EMISSIVE_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_GBUFFER_BINDING_METALLIC_ROUGHNESS_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_GBUFFER_BINDING_OCCLUSION_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_GBUFFER_BINDING_NORMAL_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
  auto bit = [&](uint32_t b) { return (textureBits & b) ? 1u : 0u; };
  d.fragmentSpecialization = {bit(DYNGI_MATERIAL_BASE_COLOR_TEX), bit(DYNGI_MATERIAL_EMISSIVE_TEX), bit(DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX),
                              bit(DYNGI_MATERIAL_OCCLUSION_TEX), bit(DYNGI_MATERIAL_ALPHA_MASK), bit(DYNGI_MATERIAL_NORMAL_TEX)};
  d.name = "gbuffer";
  pipeline = Pipeline::graphics(ctx_, d);
  return pipeline;
}

void GBufferPass::execute(FrameContext& frame, const TextureLookup& textures) {
  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  RenderTargets& t = frame.targets;
  Image* colors[] = {&t.position, &t.normal, &t.albedo, &t.emissive};
  for (Image* c : colors)
    c->transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  t.depth.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  {
    RenderingScope rendering(cmd, t.width, t.height,
                             {colorAttachment(t.position.view()), colorAttachment(t.normal.view()), colorAttachment(t.albedo.view()),
                              colorAttachment(t.emissive.view())},
                             depthAttachment(t.depth.view()));
    drawBatched(
        frame, std::nullopt,
        [&](const DrawItem& d) -> const Pipeline& { return pipelineFor(drawTextureBits(frame, d)); },
        [&](VkCommandBuffer c, const DrawItem& d, const Pipeline& pipeline) {
          const scene::Material& m = frame.snapshot.materialOf(d);
          DescriptorWrites()
              .uniformBuffer(DYNGI_GBUFFER_BINDING_FRAME, frame.frameUniforms.handle())
              .storageBuffer(DYNGI_GBUFFER_BINDING_INSTANCES, frame.instances->records->handle())
              .sampledImage(DYNGI_GBUFFER_BINDING_BASE_COLOR_TEX, textures(m.baseColorTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
              .sampledImage(DYNGI_GBUFFER_BINDING_EMISSIVE_TEX, textures(m.emissiveTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
              .sampledImage(DYNGI_GBUFFER_BINDING_METALLIC_ROUGHNESS_TEX, textures(m.metallicRoughnessTexture), frame.linearSampler,
                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
              .sampledImage(DYNGI_GBUFFER_BINDING_OCCLUSION_TEX, textures(m.occlusionTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
              .sampledImage(DYNGI_GBUFFER_BINDING_NORMAL_TEX, textures(m.normalTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
              .push(ctx_, c, pipeline);
        });
  }
  for (Image* c : colors)
    c->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

}  // namespace dyngi::render
