#include "dyngi/engine/render/draw_pass.h"

#include "shared/gpu_types.h"

#include <algorithm>
#include <stdexcept>

namespace dyngi::render {

namespace {
VkRenderingAttachmentInfo info(const Attachment& a, VkImageLayout layout) {
  VkRenderingAttachmentInfo i{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  i.imageView = a.view;
  i.imageLayout = layout;
  i.loadOp = a.load;
  i.storeOp = a.store;
  i.clearValue = a.clear;
  return i;
}
}  // namespace

RenderingScope::RenderingScope(VkCommandBuffer cmd, uint32_t width, uint32_t height, std::initializer_list<Attachment> colors,
                               std::optional<Attachment> depth)
    : cmd_(cmd) {
  if (colors.size() > kMaxColors) throw std::invalid_argument("RenderingScope: more colour attachments than kMaxColors");
  VkRenderingAttachmentInfo color[kMaxColors];
  uint32_t n = 0;
  for (const Attachment& a : colors) color[n++] = info(a, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  VkRenderingAttachmentInfo depthInfo{};
  if (depth) depthInfo = info(*depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {width, height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = n;
  ri.pColorAttachments = n ? color : nullptr;
  ri.pDepthAttachment = depth ? &depthInfo : nullptr;
  vkCmdBeginRendering(cmd, &ri);
  setFullViewport(cmd, width, height);
}

RenderingScope::~RenderingScope() { vkCmdEndRendering(cmd_); }

uint32_t materialTextureBits(const scene::Material& m) {
  return (m.baseColorTexture != scene::kNoTexture ? DYNGI_MATERIAL_BASE_COLOR_TEX : 0u) |
         (m.emissiveTexture != scene::kNoTexture ? DYNGI_MATERIAL_EMISSIVE_TEX : 0u) |
         (m.metallicRoughnessTexture != scene::kNoTexture ? DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX : 0u) |
         (m.occlusionTexture != scene::kNoTexture ? DYNGI_MATERIAL_OCCLUSION_TEX : 0u) | (m.alphaMask ? DYNGI_MATERIAL_ALPHA_MASK : 0u) |
         (m.normalTexture != scene::kNoTexture ? DYNGI_MATERIAL_NORMAL_TEX : 0u);
}

uint32_t drawTextureBits(const FrameContext& frame, const DrawItem& d) {
  uint32_t bits = materialTextureBits(d.material);
  if ((bits & DYNGI_MATERIAL_NORMAL_TEX) && frame.snapshot.assets->mesh(d.mesh).tangents.empty()) bits &= ~uint32_t(DYNGI_MATERIAL_NORMAL_TEX);
  return bits;
}

void drawEach(const FrameContext& frame, std::optional<std::span<const size_t>> indices, const DrawPipelineFor& pipelineFor,
              const DrawSetup& setup) {
  const Pipeline* bound = nullptr;
  auto draw = [&](size_t i) {
    const GpuMesh* mesh = frame.meshes[i];
    if (!mesh || mesh->indexCount == 0) return;
    const DrawItem& d = frame.snapshot.draws[i];
    const Pipeline& pipeline = pipelineFor(d);
    if (&pipeline != bound) {
      vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.handle());
      bound = &pipeline;
    }
    setup(frame.cmd, d, pipeline);
    drawMesh(frame.cmd, *mesh);
  };
  if (indices) {
    for (size_t i : *indices) draw(i);
  } else {
    for (size_t i = 0; i < frame.snapshot.draws.size(); ++i) draw(i);
  }
}

}  // namespace dyngi::render
