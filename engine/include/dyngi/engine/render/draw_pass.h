#pragma once
// What every raster pass repeats, written once: dynamic rendering over a set of attachments with the
// viewport covering the target, and the loop over the frame's draws in instanced batches (draws with no
// GPU geometry skipped, a pipeline bound only when it changes, one draw call per batch).
#include <functional>
#include <initializer_list>
#include <optional>
#include <span>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/scene/alpha_cut.h"

namespace dyngi::render {

struct Attachment {
  VkImageView view = VK_NULL_HANDLE;
  VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR;
  VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
  VkClearValue clear{};
};
// A colour attachment cleared to `clear` (or loaded).
inline Attachment colorAttachment(VkImageView view, VkClearColorValue clear = {}, VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR) {
  Attachment a{view, load, VK_ATTACHMENT_STORE_OP_STORE, {}};
  a.clear.color = clear;
  return a;
}
// A depth attachment cleared to 1 (or loaded).
inline Attachment depthAttachment(VkImageView view, VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                  VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE) {
  Attachment a{view, load, store, {}};
  a.clear.depthStencil = {1.0f, 0};
  return a;
}

// Dynamic rendering from construction to destruction: colour attachments in COLOR_ATTACHMENT_OPTIMAL,
// the depth attachment in DEPTH_ATTACHMENT_OPTIMAL (the caller transitions them), render area and
// viewport width x height. No attachments at all is allowed (a pass that only stores from fragments).
class RenderingScope {
 public:
  static constexpr size_t kMaxColors = 8;
  RenderingScope(VkCommandBuffer cmd, uint32_t width, uint32_t height, std::initializer_list<Attachment> colors = {},
                 std::optional<Attachment> depth = std::nullopt);
  ~RenderingScope();
  RenderingScope(const RenderingScope&) = delete;
  RenderingScope& operator=(const RenderingScope&) = delete;

 private:
  VkCommandBuffer cmd_;
};

// Picks a draw's pipeline (bound when it differs from the last draw's).
using DrawPipelineFor = std::function<const Pipeline&(const DrawItem&)>;
// The textures a material binds, as DYNGI_MATERIAL_*_TEX bits (shared/gpu_types.h): what the raster
// passes' pipeline variants are chosen by (a lookup not taken still costs on lavapipe).
uint32_t materialTextureBits(const scene::Material& material);
// A draw's bits: its material's, less the normal texture when its mesh has no tangents (the frame a
// normal texture turns needs them, GpuMesh::tangents).
uint32_t drawTextureBits(const FrameContext& frame, const DrawItem& draw);
// A masked material's cut, as a threshold on the base-colour texture's alpha (scene/alpha_cut.h).
// Shaders: `if (textureAlpha < threshold) discard;`.
using scene::alphaMaskThreshold;
// Records a batch's descriptors and push constants (the pass's, and the FrameInstances records the
// vertex stage reads at gl_InstanceIndex); `first` is one of its draws, whose pipeline, mesh and
// material textures all of them share. drawBatched then binds the mesh and draws the batch.
using BatchSetup = std::function<void(VkCommandBuffer, const DrawItem& first, const Pipeline&)>;

// The snapshot's draws `indices` (all of them when nullopt) that have GPU geometry, as instanced draws:
// one per run of FrameInstances slots with one batch, instances at their slots (firstInstance). The
// order within a batch is the snapshot's; between batches it is FrameInstances' (depth-tested passes and
// appends do not depend on it).
void drawBatched(const FrameContext& frame, std::optional<std::span<const size_t>> indices, const DrawPipelineFor& pipelineFor,
                 const BatchSetup& setup);

// The batches drawBatched draws, for a pass that handles them itself (a compute pass over instances):
// `first` is one of the batch's draws, its instances at FrameInstances slots [firstSlot, firstSlot + count).
using BatchVisitor = std::function<void(const DrawItem& first, const GpuMesh& mesh, uint32_t firstSlot, uint32_t count)>;
void forEachBatch(const FrameContext& frame, std::optional<std::span<const size_t>> indices, const BatchVisitor& visit);

// Builds FrameInstances for a snapshot: batches by mesh and textures, records written to `records`
// (host-visible, grown as needed; frames are synchronous, so the last frame's are no longer read).
void buildFrameInstances(VulkanContext& ctx, const RenderSnapshot& snapshot, const std::vector<GpuMesh*>& meshes, Buffer& records,
                         FrameInstances& out);

}  // namespace dyngi::render
