#include "dyngi/engine/render/draw_pass.h"

#include "shared/gpu_types.h"

#include <algorithm>
#include <array>
#include <bit>
#include <compare>
#include <numeric>

#include <glm/gtc/packing.hpp>
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
  uint32_t bits = materialTextureBits(frame.snapshot.materialOf(d));
  if ((bits & DYNGI_MATERIAL_NORMAL_TEX) && frame.snapshot.assets->mesh(d.mesh).tangents.empty()) bits &= ~uint32_t(DYNGI_MATERIAL_NORMAL_TEX);
  return bits;
}

namespace {
// What decides a batch: the mesh, and the textures and alpha mode every pass's pipeline variant and
// descriptors follow from.
struct BatchKey {
  const GpuMesh* mesh;
  std::array<scene::TextureId, 5> textures;
  bool alphaMask;
  auto operator<=>(const BatchKey&) const = default;
};
BatchKey batchKey(const RenderSnapshot& snapshot, const DrawItem& d, const GpuMesh* mesh) {
  const scene::Material& m = snapshot.materialOf(d);
  return {mesh, {m.baseColorTexture, m.emissiveTexture, m.metallicRoughnessTexture, m.occlusionTexture, m.normalTexture}, m.alphaMask};
}

gpu::DrawMaterialRecord materialRecord(const scene::Material& m) {
  gpu::DrawMaterialRecord r;
  r.baseColor = glm::vec4(glm::vec3(m.baseColor), m.alphaMask ? alphaMaskThreshold(m) : 1.0f);
  r.emissive = glm::vec4(m.emissive, std::bit_cast<float>(glm::packHalf2x16(glm::vec2(m.occlusionStrength, m.normalScale))));
  r.params = glm::vec4(m.metallic, m.roughness, m.uvTransform.offset);
  r.uvLinear = m.uvTransform.linear();
  return r;
}
}  // namespace

void buildFrameInstances(VulkanContext& ctx, const RenderSnapshot& snapshot, const std::vector<GpuMesh*>& meshes, Buffer& records,
                         FrameInstances& out) {
  const size_t n = snapshot.draws.size();
  std::vector<BatchKey> keys(n);
  for (size_t i = 0; i < n; ++i) keys[i] = batchKey(snapshot, snapshot.draws[i], meshes[i]);
  out.drawOfSlot.resize(n);
  std::iota(out.drawOfSlot.begin(), out.drawOfSlot.end(), 0u);
  std::stable_sort(out.drawOfSlot.begin(), out.drawOfSlot.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  out.slotOfDraw.resize(n);
  out.batchOfSlot.resize(n);
  static_assert(sizeof(gpu::DrawRecord) == sizeof(gpu::DrawMaterialRecord));
  const size_t materials = snapshot.materials.size();
  const VkDeviceSize bytes = (n + materials) * sizeof(gpu::DrawRecord);
  if (!records.valid() || records.size() < bytes)
    records = Buffer(ctx, records.valid() ? bytes + bytes / 2 : bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "draw records");
  auto* mapped = static_cast<gpu::DrawRecord*>(records.mapped());
  auto* materialRecords = reinterpret_cast<gpu::DrawMaterialRecord*>(mapped + n);
  for (size_t m = 0; m < materials; ++m) materialRecords[m] = materialRecord(snapshot.materials[m]);
  uint32_t batch = 0;
  for (uint32_t slot = 0; slot < n; ++slot) {
    const uint32_t draw = out.drawOfSlot[slot];
    out.slotOfDraw[draw] = slot;
    if (slot > 0 && keys[draw] != keys[out.drawOfSlot[slot - 1]]) ++batch;
    out.batchOfSlot[slot] = batch;
    const DrawItem& d = snapshot.draws[draw];
    const glm::mat4 rows = glm::transpose(d.model);
    mapped[slot] = gpu::DrawRecord{{rows[0], rows[1], rows[2]}, glm::uvec4(uint32_t(n) + d.material, 0u, 0u, 0u)};
  }
  records.flush();
  out.records = &records;
}

void forEachBatch(const FrameContext& frame, std::optional<std::span<const size_t>> indices, const BatchVisitor& visit) {
  const FrameInstances& inst = *frame.instances;
  std::vector<uint32_t> slots;
  if (indices) {
    slots.reserve(indices->size());
    for (size_t i : *indices) slots.push_back(inst.slotOfDraw[i]);
    std::sort(slots.begin(), slots.end());
  } else {
    slots.resize(frame.snapshot.draws.size());
    std::iota(slots.begin(), slots.end(), 0u);
  }
  for (size_t k = 0; k < slots.size();) {
    const uint32_t first = slots[k];
    size_t end = k + 1;
    while (end < slots.size() && slots[end] == slots[end - 1] + 1 && inst.batchOfSlot[slots[end]] == inst.batchOfSlot[first]) ++end;
    const uint32_t count = uint32_t(end - k);
    k = end;
    const size_t drawIndex = inst.drawOfSlot[first];
    const GpuMesh* mesh = frame.meshes[drawIndex];
    if (!mesh || mesh->indexCount == 0) continue;
    visit(frame.snapshot.draws[drawIndex], *mesh, first, count);
  }
}

void drawBatched(const FrameContext& frame, std::optional<std::span<const size_t>> indices, const DrawPipelineFor& pipelineFor,
                 const BatchSetup& setup) {
  const Pipeline* bound = nullptr;
  forEachBatch(frame, indices, [&](const DrawItem& d, const GpuMesh& mesh, uint32_t first, uint32_t count) {
    const Pipeline& pipeline = pipelineFor(d);
    if (&pipeline != bound) {
      vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.handle());
      bound = &pipeline;
    }
    setup(frame.cmd, d, pipeline);
    bindMesh(frame.cmd, mesh);
    vkCmdDrawIndexed(frame.cmd, mesh.indexCount, count, 0, 0, first);
  });
}

}  // namespace dyngi::render
