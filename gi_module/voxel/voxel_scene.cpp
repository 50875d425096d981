#include "dyngi/gi/voxel_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "dyngi/engine/render/draw_pass.h"
#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/scene/animation.h"
#include "shaders/shared/gi_gpu_types.h"
#include "spirv/svo_expand.comp.spv.h"
#include "spirv/svo_leaf_attributes.comp.spv.h"
#include "spirv/svo_level.comp.spv.h"
#include "spirv/svo_mark.comp.spv.h"
#include "spirv/voxel_debug.comp.spv.h"
#include "spirv/voxelize.frag.spv.h"
#include "spirv/voxelize.geom.spv.h"
#include "spirv/voxelize.vert.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

const OptionTable<VoxelSettings>& VoxelSettings::table() {
  static const OptionTable<VoxelSettings> t = OptionTable<VoxelSettings>().add(
      {"voxel-res", "voxel volume resolution (the SVO's finest level)", 64, 512, /*powerOfTwo=*/true}, &VoxelSettings::resolution);
  return t;
}

namespace {
constexpr uint32_t kAttributeInts = 8;  // ints per leaf in the attribute buffer
constexpr uint32_t kMinNodeGroups = 1u << 12;  // the node pool never shrinks below this (128 KB)
}  // namespace

VoxelScene::VoxelScene(render::VulkanContext& ctx, const VoxelSettings& settings) : ctx_(ctx), settings_(settings) {
  uint32_t r = settings.resolution;
  if (r < 8 || r > 1024 || (r & (r - 1)) != 0)
    throw std::invalid_argument("voxel resolution must be a power of two in 8..1024, got " + std::to_string(r));

  const Binding markB[] = {{DYNGI_SVO_MARK_BINDING_FRAGMENTS, kSSBO, kCS},
                           {DYNGI_SVO_MARK_BINDING_OCCUPANCY, kSSBO, kCS},
                           {DYNGI_SVO_MARK_BINDING_CHUNKS, kSSBO, kCS}};
  mark_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_mark_comp), markB, sizeof(gpu::SvoMarkPush), "svo_mark");
  const Binding levelB[] = {{DYNGI_SVO_LEVEL_BINDING_LEVELS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_COUNTERS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_NODES, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_NODE_CELLS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_OCCUPANCY, kSSBO, kCS}};
  level_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_level_comp), levelB, sizeof(gpu::SvoLevelPush), "svo_level");
  const Binding expandB[] = {{DYNGI_SVO_EXPAND_BINDING_NODES, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_NODE_CELLS, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_OCCUPANCY, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_LEVELS, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_COUNTERS, kSSBO, kCS}};
  expand_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_expand_comp), expandB, sizeof(gpu::SvoExpandPush), "svo_expand");
  const Binding attrB[] = {{DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES, kSSBO, kCS}};
  leafAttributes_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_leaf_attributes_comp), attrB, sizeof(gpu::SvoLeafAttributesPush),
                                     "svo_leaf_attributes");
  // One bit per cell of every level 0..depth (DYNGI_SVO_LEVEL_BASE): level depth + 1 would start here.
  uint32_t depth = 0;
  while ((1u << depth) < settings_.resolution) ++depth;
  const uint64_t pyramidBits = 8 + 8 * (((uint64_t(1) << (3 * depth)) - 1) / 7);
  occupancy_ = Buffer(ctx, (pyramidBits + 31) / 32 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      MemoryUsage::GpuOnly, "svo occupancy pyramid");
  staticOccupancy_ = Buffer(ctx, occupancy_.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            MemoryUsage::GpuOnly, "svo static occupancy pyramid");
  const Binding debugB[] = {{DYNGI_VOXEL_DEBUG_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_NODES, kSSBO, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_LEVELS, kSSBO, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_ATTRIBUTES, kSSBO, kCS},
                            {DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS}};
  debug_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_voxel_debug_comp), debugB, sizeof(gpu::VoxelDebugPush), "voxel_debug");

  // The first build gets the whole pool; afterwards it follows what the SVO uses (resizeNodePool).
  nodeGroupCapacity_ = std::max(settings.maxNodeGroups, 2u);
  nodes_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  nodeCells_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  levels_ = Buffer(ctx, sizeof(gpu::SvoLevel) * DYNGI_SVO_MAX_LEVELS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                   MemoryUsage::Readback, "svo levels");
  svoCounters_ = Buffer(ctx, sizeof(gpu::SvoCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        MemoryUsage::Readback, "svo counters");
  reallocateFragments(1u << 16, {});
}

VoxelScene::~VoxelScene() = default;

void VoxelScene::setDebugView(VoxelDebugView v) {
  settings_.debugView = v;
  if (v == VoxelDebugView::Voxels && !settings_.leafAttributes) {  // the view colours voxels by albedo
    settings_.leafAttributes = true;
    vkDeviceWaitIdle(ctx_.device());
    attributes_ = Buffer(ctx_, stats_.fragmentCapacity * kAttributeInts * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly,
                         "voxel leaf attributes");
    storageMoved_ = true;  // build them
  }
}

void VoxelScene::setVolume(const VoxelVolume& v) {
  volume_ = v;
  volume_.resolution = settings_.resolution;
  haveVolume_ = true;
  allDirty_ = true;
}

void VoxelScene::ensureCapacity(uint64_t slots) {
  if (fragments_.valid() && fragments_.size() >= slots * 16) return;
  std::vector<SlotCopy> keep;
  if (fragments_.valid() && ranges_.highWater() > 0) keep.push_back({0, 0, ranges_.highWater()});
  reallocateFragments(std::max<uint64_t>(slots + slots / 2, 1u << 16), keep);
}

void VoxelScene::reallocateFragments(uint64_t slots, const std::vector<SlotCopy>& keepSlots) {
  std::vector<VkBufferCopy> keep;
  for (const SlotCopy& c : keepSlots) keep.push_back({c.from * 16, c.to * 16, c.count * 16});
  vkDeviceWaitIdle(ctx_.device());
  Buffer fresh(ctx_, slots * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "voxel fragments");
  ctx_.immediate([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, fresh.handle(), 0, VK_WHOLE_SIZE, DYNGI_VOXEL_EMPTY);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (!keep.empty()) vkCmdCopyBuffer(cmd, fragments_.handle(), fresh.handle(), uint32_t(keep.size()), keep.data());
  });
  fragments_ = std::move(fresh);
  attributes_ = Buffer(ctx_, settings_.leafAttributes ? slots * kAttributeInts * 4 : 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       MemoryUsage::GpuOnly, "voxel leaf attributes");
  stats_.fragmentCapacity = slots;
  storageMoved_ = true;
}

void VoxelScene::compactFragments() {
  const std::vector<SlotCopy> keep = ranges_.compact();
  const uint64_t next = ranges_.highWater();
  reallocateFragments(std::max<uint64_t>(next + next / 4, FragmentRanges::kMinCompactSlots), keep);
}

void VoxelScene::prepare(render::VulkanContext&, const render::RenderSnapshot& snapshot) {
  drawsToVoxelize_.clear();
  rangesToEmpty_.clear();
  voxelizedThisFrame_.clear();
  rebuildSvo_ = false;
  stats_.rebuilt = false;
  stats_.entitiesVoxelized = 0;
  if (!snapshot.assets) return;
  ++frameIndex_;
  if (!haveVolume_) {
    volume_ = VoxelVolume::around(snapshot.sceneBounds, settings_.resolution, settings_.padding);
    haveVolume_ = true;
    allDirty_ = true;
  }
  const glm::mat4 toVoxel = volume_.worldToVoxelMatrix();

  // Entities that disappeared from the draw list count as removed.
  std::unordered_set<ecs::Entity> present;
  for (const auto& d : snapshot.draws) present.insert(d.entity);
  for (const auto& [e, r] : ranges_.all())
    if (!present.count(e)) removed_.insert(e);

  // Compact when the ranges hold more than twice what they need (counts from the last frame): after
  // the first frame, and again as moved entities leave holes.
  if (!allDirty_ && ranges_.wantsCompaction()) compactFragments();
  if (allDirty_) {
    rebuildStaticOccupancy_ = true;
    ranges_.clear();
    rangesToEmpty_.clear();
    for (const auto& d : snapshot.draws) dirty_.insert(d.entity);
    allDirty_ = false;
    rebuildSvo_ = true;
  }
  std::vector<ecs::Entity> removedNow;
  for (ecs::Entity e : removed_) {
    const std::optional<Range> r = ranges_.remove(e);
    if (!r) continue;
    removedNow.push_back(e);
    rangesToEmpty_.push_back(*r);
    rebuildSvo_ = true;
  }
  removed_.clear();
  drawsToVoxelize_.clear();
  uint64_t newHighWater = ranges_.highWater();
  std::vector<std::pair<ecs::Entity, Range>> planned;
  for (size_t i = 0; i < snapshot.draws.size(); ++i) {
    const auto& d = snapshot.draws[i];
    if (!dirty_.count(d.entity)) continue;
    const uint64_t estimate = FragmentRanges::estimateFragments(snapshot.assets->mesh(d.mesh), toVoxel * d.model);
    planned.push_back({d.entity, ranges_.plan(d.entity, estimate, newHighWater, rangesToEmpty_)});
    drawsToVoxelize_.push_back(i);
  }
  ensureCapacity(newHighWater);  // grows by copying: nothing already voxelized is lost
  for (auto& [e, r] : planned) {
    ranges_.commit(e, r, frameIndex_);
    voxelizedThisFrame_.push_back(e);
  }
  ranges_.setHighWater(newHighWater);
  dirty_.clear();
  if (!drawsToVoxelize_.empty() || storageMoved_) rebuildSvo_ = true;
  storageMoved_ = false;
  uint64_t countersBytes = uint64_t(std::max(ranges_.counterCount(), 1u)) * 4;
  if (!counters_.valid() || counters_.size() < countersBytes) {
    vkDeviceWaitIdle(ctx_.device());
    Buffer grown(ctx_, std::max<uint64_t>(countersBytes * 2, 1024), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "voxel counters");
    if (counters_.valid()) std::memcpy(grown.mapped(), counters_.mapped(), counters_.size());
    counters_ = std::move(grown);
  }
  stats_.entitiesVoxelized = uint32_t(drawsToVoxelize_.size());
  if (rebuildSvo_) planOccupancy(removedNow);
}

void VoxelScene::planOccupancy(const std::vector<ecs::Entity>& removed) {
  // The static pyramid is stale when one of its entities was voxelized again (moved, deformed) or
  // removed; it is worth rebuilding when a moving entity has settled.
  for (ecs::Entity e : voxelizedThisFrame_) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (ecs::Entity e : removed) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (const auto& [e, r] : ranges_.all()) rebuildStaticOccupancy_ |= !isMoving(r) && !staticEntities_.count(e);
  if (rebuildStaticOccupancy_) {
    staticEntities_.clear();
    for (const auto& [e, r] : ranges_.all())
      if (!isMoving(r)) staticEntities_.insert(e);
  }
  // One chunk per mark workgroup (64 invocations x DYNGI_SVO_ITEMS_PER_INVOCATION slots), cut from the
  // ranges: the static entities' first (only when the static pyramid is rebuilt), then the moving ones'.
  const uint64_t chunkSlots = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
  std::vector<glm::uvec2> chunks;
  stats_.slotsMarked = 0;
  stats_.staticEntities = uint32_t(staticEntities_.size());
  auto cut = [&](bool wantStatic) {
    uint32_t n = 0;
    for (const auto& [e, r] : ranges_.all()) {
      if (staticEntities_.count(e) != size_t(wantStatic)) continue;
      stats_.slotsMarked += r.capacity;
      for (uint64_t a = r.first; a < r.first + r.capacity; a += chunkSlots, ++n)
        chunks.push_back(glm::uvec2(uint32_t(a), uint32_t(std::min(a + chunkSlots, r.first + r.capacity))));
    }
    return n;
  };
  staticChunks_ = rebuildStaticOccupancy_ ? cut(true) : 0;
  movingChunks_ = cut(false);
  const VkDeviceSize bytes = std::max<VkDeviceSize>(chunks.size() * sizeof(glm::uvec2), 16);
  if (!markChunks_.valid() || markChunks_.size() < bytes) {
    vkDeviceWaitIdle(ctx_.device());  // the last frame may still read the old list
    markChunks_ = Buffer(ctx_, bytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "svo mark chunks");
  }
  if (!chunks.empty()) markChunks_.upload(chunks.data(), chunks.size() * sizeof(glm::uvec2));
}

void VoxelScene::recordMark(VkCommandBuffer cmd, const render::Buffer& target, uint32_t firstChunk, uint32_t chunkCount) {
  if (chunkCount == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mark_.handle());
  DescriptorWrites()
      .storageBuffer(DYNGI_SVO_MARK_BINDING_FRAGMENTS, fragments_.handle())
      .storageBuffer(DYNGI_SVO_MARK_BINDING_OCCUPANCY, target.handle())
      .storageBuffer(DYNGI_SVO_MARK_BINDING_CHUNKS, markChunks_.handle())
      .push(ctx_, cmd, mark_);
  const gpu::SvoMarkPush mp{firstChunk, volume_.depth()};
  vkCmdPushConstants(cmd, mark_.layout(), kCS, 0, sizeof(mp), &mp);
  vkCmdDispatch(cmd, chunkCount, 1, 1);
}

render::Pipeline& VoxelScene::voxelizePipelineFor(bool baseColorTexture, bool emissiveTexture) {
  Pipeline& pipeline = voxelize_[(baseColorTexture ? 1 : 0) | (emissiveTexture ? 2 : 0)];
  if (pipeline.handle()) return pipeline;
  Pipeline::GraphicsDesc d;
  d.vertex = DYNGI_SHADER(spv_voxelize_vert);
  d.geometry = DYNGI_SHADER(spv_voxelize_geom);
  d.fragment = DYNGI_SHADER(spv_voxelize_frag);
  render::setMeshVertexInput(d, /*normal=*/false, /*uv=*/true);
  d.pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  d.pushConstantBytes = sizeof(gpu::VoxelizePush);
  d.bindings = {{DYNGI_VOXELIZE_BINDING_FRAGMENTS, kSSBO, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_VOXELIZE_BINDING_COUNTERS, kSSBO, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
  d.fragmentSpecialization = {baseColorTexture ? 1u : 0u, emissiveTexture ? 1u : 0u};
  d.name = "voxelize";
  pipeline = Pipeline::graphics(ctx_, d);
  return pipeline;
}

bool VoxelScene::record(render::FrameContext& frame) {
  if (!rebuildSvo_ || !haveVolume_) return false;
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t res = volume_.resolution, depth = volume_.depth();
  {
    render::ScopedPass scope(ctx_, frame.timer, cmd, "voxelize");
    for (const Range& r : rangesToEmpty_)
      vkCmdFillBuffer(cmd, fragments_.handle(), r.first * 16, r.capacity * 16, DYNGI_VOXEL_EMPTY);
    for (size_t i : drawsToVoxelize_) {
      const Range& r = ranges_.at(frame.snapshot.draws[i].entity);
      vkCmdFillBuffer(cmd, fragments_.handle(), r.first * 16, r.capacity * 16, DYNGI_VOXEL_EMPTY);
      vkCmdFillBuffer(cmd, counters_.handle(), uint64_t(r.counter) * 4, 4, 0);
    }
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (!drawsToVoxelize_.empty()) {
      // No attachments: the fragment shader appends to the entity's range.
      render::RenderingScope rendering(cmd, res, res);
      const glm::mat4 toVoxel = volume_.worldToVoxelMatrix();
      auto pipelineFor = [&](const render::DrawItem& d) -> const Pipeline& {
        return voxelizePipelineFor(d.material.baseColorTexture != scene::kNoTexture, d.material.emissiveTexture != scene::kNoTexture);
      };
      render::drawEach(frame, drawsToVoxelize_, pipelineFor, [&](VkCommandBuffer c, const render::DrawItem& d, const Pipeline& pipeline) {
        const Range& r = ranges_.at(d.entity);
        gpu::VoxelizePush pc{};
        pc.modelToVoxel = toVoxel * d.model;
        pc.firstSlot = uint32_t(r.first);
        pc.capacity = uint32_t(r.capacity);
        pc.counterIndex = r.counter;
        pc.resolution = res;
        pc.albedo = glm::vec4(glm::vec3(d.material.baseColor) * (1.0f - d.material.metallic), 0.0f);
        pc.emission = glm::vec4(d.material.emissive, 0.0f);
        DescriptorWrites()
            .storageBuffer(DYNGI_VOXELIZE_BINDING_FRAGMENTS, fragments_.handle())
            .storageBuffer(DYNGI_VOXELIZE_BINDING_COUNTERS, counters_.handle())
            .sampledImage(DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX, frame.textureView(d.material.baseColorTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX, frame.textureView(d.material.emissiveTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .push(ctx_, c, pipeline);
        vkCmdPushConstants(c, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(pc), &pc);
      });
    }
    render::computeWriteBarrier(cmd);
  }
  {
    render::ScopedPass scope(ctx_, frame.timer, cmd, "svo_build");
    gpu::SvoCounters init{};
    init.groups = glm::uvec4(1, nodeGroupCapacity_, 0, 0);
    vkCmdUpdateBuffer(cmd, svoCounters_.handle(), 0, sizeof(init), &init);
    // 1. Every fragment marks its cells in the occupancy pyramid: the static entities' once into the
    // static pyramid, which each build copies, then the moving entities' on top.
    if (rebuildStaticOccupancy_) {
      vkCmdFillBuffer(cmd, staticOccupancy_.handle(), 0, VK_WHOLE_SIZE, 0);
      render::computeWriteBarrier(cmd);
      recordMark(cmd, staticOccupancy_, 0, staticChunks_);
      render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
      rebuildStaticOccupancy_ = false;
    }
    const VkBufferCopy whole{0, 0, occupancy_.size()};
    vkCmdCopyBuffer(cmd, staticOccupancy_.handle(), occupancy_.handle(), 1, &whole);
    render::computeWriteBarrier(cmd);
    recordMark(cmd, occupancy_, staticChunks_, movingChunks_);
    render::computeWriteBarrier(cmd);
    const uint32_t slots = uint32_t(ranges_.highWater());
    const uint32_t perGroup = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
    // 2. Top down, level by level: the occupied nodes get their children, flagged from the pyramid.
    for (uint32_t l = 0; l <= depth; ++l) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, level_.handle());
      DescriptorWrites()
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_LEVELS, levels_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_COUNTERS, svoCounters_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_NODES, nodes_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_NODE_CELLS, nodeCells_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_OCCUPANCY, occupancy_.handle())
          .push(ctx_, cmd, level_);
      const gpu::SvoLevelPush lp{l};
      vkCmdPushConstants(cmd, level_.layout(), kCS, 0, sizeof(lp), &lp);
      vkCmdDispatch(cmd, 1, 1, 1);
      render::computeWriteBarrier(cmd);
      if (l == depth) break;  // leaves: their range is known, they are never subdivided
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, expand_.handle());
      DescriptorWrites()
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_NODES, nodes_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_NODE_CELLS, nodeCells_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_OCCUPANCY, occupancy_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_LEVELS, levels_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_COUNTERS, svoCounters_.handle())
          .push(ctx_, cmd, expand_);
      const gpu::SvoExpandPush ep{l, depth};
      vkCmdPushConstants(cmd, expand_.layout(), kCS, 0, sizeof(ep), &ep);
      vkCmdDispatchIndirect(cmd, levels_.handle(), VkDeviceSize(l) * sizeof(gpu::SvoLevel) + offsetof(gpu::SvoLevel, dispatch));
      render::computeWriteBarrier(cmd);
    }
    if (settings_.leafAttributes) {
      // Leaf attributes, kept apart from the nodes.
      vkCmdFillBuffer(cmd, attributes_.handle(), 0, VK_WHOLE_SIZE, 0);
      render::computeWriteBarrier(cmd);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, leafAttributes_.handle());
      DescriptorWrites()
          .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS, fragments_.handle())
          .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES, nodes_.handle())
          .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS, levels_.handle())
          .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES, attributes_.handle())
          .push(ctx_, cmd, leafAttributes_);
      const gpu::SvoLeafAttributesPush ap{depth, uint32_t(stats_.fragmentCapacity), slots};
      vkCmdPushConstants(cmd, leafAttributes_.layout(), kCS, 0, sizeof(ap), &ap);
      vkCmdDispatch(cmd, std::max(dispatchGroups(slots, perGroup), 1u), 1, 1);
      render::computeWriteBarrier(cmd);
    }
  }
  stats_.rebuilt = true;
  return false;  // the voxel scene feeds other stages; it does not write indirect light
}

void VoxelScene::recordAfterLighting(render::FrameContext& frame) {
  if (settings_.debugView == VoxelDebugView::None || !haveVolume_) return;
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "voxel_debug_view");
  render::RenderTargets& t = frame.targets;
  t.hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, debug_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VOXEL_DEBUG_BINDING_FRAME, frame.frameUniforms.handle())
      .storageBuffer(DYNGI_VOXEL_DEBUG_BINDING_NODES, nodes_.handle())
      .storageBuffer(DYNGI_VOXEL_DEBUG_BINDING_LEVELS, levels_.handle())
      .storageBuffer(DYNGI_VOXEL_DEBUG_BINDING_ATTRIBUTES, attributes_.handle())
      .storageImage(DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR, t.hdr.view())
      .push(ctx_, frame.cmd, debug_);
  const gpu::VoxelDebugPush pc{glm::vec4(volume_.origin, 1.0f / volume_.voxelSize), volume_.depth(), float(volume_.resolution),
                               settings_.debugView == VoxelDebugView::SvoSteps ? 1u : 0u};
  vkCmdPushConstants(frame.cmd, debug_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(frame.cmd, (t.width + 7) / 8, (t.height + 7) / 8, 1);
}

void VoxelScene::frameFinished(render::VulkanContext&) {
  if (!stats_.rebuilt) return;
  counters_.invalidateForRead();
  svoCounters_.invalidateForRead();
  const uint32_t* counts = static_cast<const uint32_t*>(counters_.mapped());
  stats_.overflowedEntities = 0;
  for (ecs::Entity e : voxelizedThisFrame_) {
    Range& r = ranges_.at(e);
    r.lastCount = counts[r.counter];
    if (r.lastCount > r.capacity) {
      ++stats_.overflowedEntities;
      dirty_.insert(e);  // next frame: a larger range
    }
  }
  stats_.fragments = ranges_.storedFragments();
  const auto* c = static_cast<const gpu::SvoCounters*>(svoCounters_.mapped());
  uint64_t groups = std::min<uint64_t>(c->groups.x, c->groups.y);
  stats_.nodes = groups * 8;
  stats_.leaves = c->groups.w;
  stats_.poolOverflow = c->groups.z != 0;
  stats_.svoBytes = stats_.nodes * 4;
  if (stats_.poolOverflow && nodeGroupCapacity_ >= settings_.maxNodeGroups)
    std::fprintf(stderr, "dyngi: warning: SVO node pool overflow (%u groups); raise maxNodeGroups\n", settings_.maxNodeGroups);
  // Keep the pool between 4/3 and 8 times what the SVO uses: grow before it fills (an overflowing build
  // is conservative: childless nodes count as occupied, so it is rebuilt next frame), shrink after the
  // first build, which had the whole pool.
  uint64_t want = nodeGroupCapacity_;
  if (stats_.poolOverflow || groups * 4 > uint64_t(nodeGroupCapacity_) * 3) want = std::max<uint64_t>(2ull * nodeGroupCapacity_, 2 * groups);
  else if (groups * 8 < nodeGroupCapacity_) want = 2 * groups;
  want = std::clamp<uint64_t>(want, std::min<uint32_t>(kMinNodeGroups, settings_.maxNodeGroups), settings_.maxNodeGroups);
  if (want != nodeGroupCapacity_) resizeNodePool(uint32_t(want), groups);
  if (stats_.poolOverflow && want > groups) storageMoved_ = true;  // the conservative SVO stands until the next build
  stats_.totalBytes = fragments_.size() + nodes_.size() + nodeCells_.size() + occupancy_.size() + attributes_.size();
}

void VoxelScene::resizeNodePool(uint32_t groups, uint64_t keepGroups) {
  vkDeviceWaitIdle(ctx_.device());
  Buffer fresh(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  keepGroups = std::min<uint64_t>(keepGroups, groups);
  if (keepGroups > 0)  // the current SVO stays readable until the next build
    ctx_.immediate([&](VkCommandBuffer cmd) {
      VkBufferCopy copy{0, 0, keepGroups * 8 * 4};
      vkCmdCopyBuffer(cmd, nodes_.handle(), fresh.handle(), 1, &copy);
    });
  nodes_ = std::move(fresh);
  nodeCells_ = Buffer(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  nodeGroupCapacity_ = groups;
}

void VoxelSyncSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  apply(tracker_.compute(world, assets_, ctx.lastRun));
}

void VoxelSyncSystem::apply(const ChangeSet& changes) {
  // Deforming meshes are in `deformed`: their vertices change without any component write.
  for (const auto* list : {&changes.moved, &changes.meshWritten, &changes.materials, &changes.deformed})
    for (ecs::Entity e : *list) voxels_.markDirty(e);
  for (ecs::Entity e : changes.removed) voxels_.markRemoved(e);
}

}  // namespace dyngi::gi
