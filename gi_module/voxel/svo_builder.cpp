#include "voxel/svo_builder.h"

#include <algorithm>
#include <cstdio>
#include <cstddef>

#include "dyngi/engine/render/gpu_timer.h"
#include "voxel/shaders/voxel_shared.h"
#include "spirv/svo_expand.comp.spv.h"
#include "spirv/svo_leaf_attributes.comp.spv.h"
#include "spirv/svo_level.comp.spv.h"
#include "spirv/svo_mark.comp.spv.h"
#include "spirv/svo_voxel_attributes.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

namespace {
constexpr uint32_t kMinNodeGroups = 1u << 12;  // the node pool never shrinks below this (128 KB)
// The leaf list holds at most one entry per node of the pool, after its header.
VkDeviceSize leafListBytes(uint32_t groups) { return (VkDeviceSize(groups) * 8 * DYNGI_SVO_LEAF_ENTRY_UINTS + DYNGI_SVO_LEAF_LIST_HEADER) * 4; }
uint32_t depthOf(uint32_t resolution) {
  uint32_t depth = 0;
  while ((1u << depth) < resolution) ++depth;
  return depth;
}
// The groups a full tree of `depth` takes: the root's, then one per node of levels 0..depth-1 (8^l
// each), so a pool this large never overflows (at 128^3, 299,594 groups: 38 MB with the leaf list).
uint64_t fullTreeGroups(uint32_t depth) {
  uint64_t groups = 1;
  for (uint32_t l = 0; l < depth; ++l) groups += uint64_t(1) << (3 * l);
  return groups;
}
}  // namespace

SvoBuilder::SvoBuilder(render::VulkanContext& ctx, uint32_t resolution, uint32_t maxNodeGroups)
    : ctx_(ctx), maxNodeGroups_(uint32_t(std::min<uint64_t>(maxNodeGroups, fullTreeGroups(depthOf(resolution))))) {
  const Binding markB[] = {{DYNGI_SVO_MARK_BINDING_FRAGMENTS, kSSBO, kCS},
                           {DYNGI_SVO_MARK_BINDING_OCCUPANCY, kSSBO, kCS},
                           {DYNGI_SVO_MARK_BINDING_CHUNKS, kSSBO, kCS},
                           {DYNGI_SVO_MARK_BINDING_COUNTERS, kSSBO, kCS}};
  mark_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_mark_comp), markB, sizeof(gpu::SvoMarkPush), "svo_mark");
  const Binding levelB[] = {{DYNGI_SVO_LEVEL_BINDING_LEVELS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_COUNTERS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_NODES, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_NODE_CELLS, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_OCCUPANCY, kSSBO, kCS},
                            {DYNGI_SVO_LEVEL_BINDING_LEAF_LIST, kSSBO, kCS}};
  level_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_level_comp), levelB, sizeof(gpu::SvoLevelPush), "svo_level");
  const Binding expandB[] = {{DYNGI_SVO_EXPAND_BINDING_NODES, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_NODE_CELLS, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_OCCUPANCY, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_LEVELS, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_COUNTERS, kSSBO, kCS},
                             {DYNGI_SVO_EXPAND_BINDING_LEAF_LIST, kSSBO, kCS}};
  expand_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_expand_comp), expandB, sizeof(gpu::SvoExpandPush), "svo_expand");
  const Binding attrB[] = {{DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_CHUNKS, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_MOVING, kSSBO, kCS},
                           {DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_COUNTERS, kSSBO, kCS}};
  for (uint32_t emission : {0u, 1u}) {
    const uint32_t spec[] = {emission};
    leafAttributes_[emission] = render::LazyPipeline::compute(ctx, DYNGI_SHADER(spv_svo_leaf_attributes_comp), attrB, sizeof(gpu::SvoLeafAttributesPush),
                                                  "svo_leaf_attributes", spec);
  }
  const Binding voxelB[] = {{DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEAF_LIST, kSSBO, kCS},
                            {DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEVELS, kSSBO, kCS},
                            {DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_SUMS, kSSBO, kCS},
                            {DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_VOXELS, kStorageImage, kCS},
                            {DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_MOVING, kSSBO, kCS}};
  for (uint32_t step = 0; step < 4; ++step) {
    const uint32_t spec[] = {step};
    voxelAttributes_[step] = render::LazyPipeline::compute(ctx, DYNGI_SHADER(spv_svo_voxel_attributes_comp), voxelB, sizeof(gpu::SvoVoxelAttributesPush),
                                               "svo_voxel_attributes", spec);
  }
  static_assert(DYNGI_VOXEL_ATTRIBUTES_STEP_STATIC == 0 && DYNGI_VOXEL_ATTRIBUTES_STEP_MERGE == 3, "voxelAttributes_ is indexed by step");
  // One bit per cell of every level 0..depth (DYNGI_SVO_LEVEL_BASE): level depth + 1 would start here.
  const uint32_t depth = depth_ = depthOf(resolution);
  const uint64_t pyramidBits = 8 + 8 * (((uint64_t(1) << (3 * depth)) - 1) / 7);
  for (Buffer& pyramid : occupancy_)
    pyramid = Buffer(ctx, (pyramidBits + 31) / 32 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     MemoryUsage::GpuOnly, "svo occupancy pyramid");
  staticOccupancy_ = Buffer(ctx, occupancy_[0].size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            MemoryUsage::GpuOnly, "svo static occupancy pyramid");
  // The first build gets the whole pool unless fitFirstPool cuts it; afterwards the pool follows what
  // the SVO uses (resizeNodePool).
  nodeGroupCapacity_ = std::max(maxNodeGroups_, 2u);
  nodes_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  nodeCells_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  leafList_ = Buffer(ctx, leafListBytes(nodeGroupCapacity_), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                     MemoryUsage::GpuOnly, "svo leaf list");
  levels_ = Buffer(ctx, sizeof(gpu::SvoLevel) * DYNGI_SVO_MAX_LEVELS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                   MemoryUsage::Readback, "svo levels");
  svoCounters_ = Buffer(ctx, sizeof(gpu::SvoCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        MemoryUsage::Readback, "svo counters");
  // Empty until built: the pyramid a first build sees as the one before it.
  ctx.immediate([&](VkCommandBuffer cmd) {
    for (const Buffer& pyramid : occupancy_) vkCmdFillBuffer(cmd, pyramid.handle(), 0, VK_WHOLE_SIZE, 0);
  });
}

void SvoBuilder::plan(const FragmentRanges& ranges, uint64_t frame, const std::vector<ecs::Entity>& voxelized,
                      const std::vector<ecs::Entity>& removed, VoxelStats& stats) {
  auto isMoving = [&](const FragmentRange& r) { return FragmentRanges::isMoving(r, frame); };
  // The static pyramid is stale when one of its entities was voxelized again (moved, deformed) or
  // removed; it is worth rebuilding when a moving entity has settled.
  for (ecs::Entity e : voxelized) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (ecs::Entity e : removed) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (const auto& [e, r] : ranges.all()) rebuildStaticOccupancy_ |= !isMoving(r) && !staticEntities_.count(e);
  if (rebuildStaticOccupancy_) {
    staticEntities_.clear();
    for (const auto& [e, r] : ranges.all())
      if (!isMoving(r)) staticEntities_.insert(e);
  }
  // One chunk per mark workgroup (64 invocations x DYNGI_SVO_ITEMS_PER_INVOCATION slots), cut from the
  // ranges: the static entities' first (only when the static pyramid is rebuilt), then the moving ones'.
  // A range of over half a chunk is cut alone, its chunks' ends from its counter; smaller ranges that
  // follow each other in the storage share one (200,000 small instances: 200,000 workgroups of six
  // fragments each otherwise).
  const uint64_t chunkSlots = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
  std::vector<glm::uvec4> chunks;  // DYNGI_SVO_CHUNK
  stats.slotsMarked = 0;
  stats.staticEntities = uint32_t(staticEntities_.size());
  std::vector<const FragmentRange*> small;
  auto cut = [&](bool wantStatic) {
    const size_t before = chunks.size();
    small.clear();
    for (const auto& [e, r] : ranges.all()) {
      if (staticEntities_.count(e) != size_t(wantStatic)) continue;
      stats.slotsMarked += r.capacity;
      if (2 * r.capacity <= chunkSlots) {
        small.push_back(&r);
        continue;
      }
      for (uint64_t a = r.first; a < r.first + r.capacity; a += chunkSlots)
        chunks.push_back(glm::uvec4(uint32_t(a), uint32_t(std::min(a + chunkSlots, r.first + r.capacity)), uint32_t(r.first), r.counter));
    }
    std::sort(small.begin(), small.end(), [](const FragmentRange* a, const FragmentRange* b) { return a->first < b->first; });
    bool open = false;
    for (const FragmentRange* r : small) {
      if (open && chunks.back().y == r->first && r->first + r->capacity - chunks.back().x <= chunkSlots) {
        chunks.back().y = uint32_t(r->first + r->capacity);
        chunks.back().w = DYNGI_SVO_CHUNK_NO_COUNTER;  // several ranges: their empty slots are skipped instead
        continue;
      }
      chunks.push_back(glm::uvec4(uint32_t(r->first), uint32_t(r->first + r->capacity), uint32_t(r->first), r->counter));
      open = true;
    }
    return uint32_t(chunks.size() - before);
  };
  staticChunks_ = rebuildStaticOccupancy_ ? cut(true) : 0;
  const uint64_t slotsBeforeMoving = stats.slotsMarked;
  movingChunks_ = cut(false);
  // The moving leaves: at most one a slot of the moving ranges. Grown keeping the last build's (the next
  // build restores their voxels); zero at first (no last build).
  const VkDeviceSize movingBytes = (1 + 2 * std::max<uint64_t>(stats.slotsMarked - slotsBeforeMoving, 64)) * 16;
  if (!movingLeaves_.valid() || movingLeaves_.size() < movingBytes) {
    vkDeviceWaitIdle(ctx_.device());
    Buffer grown(ctx_, movingBytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::GpuOnly, "svo moving leaves");
    ctx_.immediate([&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, grown.handle(), 0, VK_WHOLE_SIZE, 0);
      if (!movingLeaves_.valid()) return;
      render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const VkBufferCopy keep{0, 0, movingLeaves_.size()};
      vkCmdCopyBuffer(cmd, movingLeaves_.handle(), grown.handle(), 1, &keep);
    });
    movingLeaves_ = std::move(grown);
  }
  const VkDeviceSize bytes = std::max<VkDeviceSize>(chunks.size() * sizeof(glm::uvec4), 16);
  if (!markChunks_.valid() || markChunks_.size() < bytes) {
    vkDeviceWaitIdle(ctx_.device());  // the last frame may still read the old list
    markChunks_ = Buffer(ctx_, bytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "svo mark chunks");
  }
  if (!chunks.empty()) markChunks_.upload(chunks.data(), chunks.size() * sizeof(glm::uvec4));
}

void SvoBuilder::recordMark(VkCommandBuffer cmd, const render::Buffer& fragments, const render::Buffer& target, uint32_t depth,
                            uint32_t firstChunk, uint32_t chunkCount) {
  if (chunkCount == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mark_.handle());
  DescriptorWrites()
      .storageBuffer(DYNGI_SVO_MARK_BINDING_FRAGMENTS, fragments.handle())
      .storageBuffer(DYNGI_SVO_MARK_BINDING_OCCUPANCY, target.handle())
      .storageBuffer(DYNGI_SVO_MARK_BINDING_CHUNKS, markChunks_.handle())
      .storageBuffer(DYNGI_SVO_MARK_BINDING_COUNTERS, counters_->handle())
      .push(ctx_, cmd, mark_);
  const gpu::SvoMarkPush mp{firstChunk, depth};
  vkCmdPushConstants(cmd, mark_.layout(), kCS, 0, sizeof(mp), &mp);
  vkCmdDispatch(cmd, chunkCount, 1, 1);
}

void SvoBuilder::recordLeafSums(VkCommandBuffer cmd, const render::Buffer& fragments, uint32_t depth, const LeafAttributeTargets& attributes,
                                uint32_t firstChunk, uint32_t chunkCount, bool listLeaves) {
  if (chunkCount == 0) return;
  const Pipeline& pipeline = leafAttributes_[attributes.emission ? 1 : 0].get();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  DescriptorWrites()
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS, fragments.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES, nodes_.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS, levels_.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES, attributes.sums.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_CHUNKS, markChunks_.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_MOVING, movingLeaves_.handle())
      .storageBuffer(DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_COUNTERS, counters_->handle())
      .push(ctx_, cmd, pipeline);
  const gpu::SvoLeafAttributesPush ap{depth, uint32_t(attributes.leafCapacity), firstChunk, listLeaves ? 1u : 0u};
  vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, sizeof(ap), &ap);
  vkCmdDispatch(cmd, chunkCount, 1, 1);
  render::computeWriteBarrier(cmd);
}

void SvoBuilder::recordVoxelAttributes(VkCommandBuffer cmd, uint32_t step, uint32_t depth, const LeafAttributeTargets& attributes,
                                       const render::Buffer& args, VkDeviceSize argsOffset) {
  const Pipeline& pipeline = voxelAttributes_[step].get();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  DescriptorWrites()
      .storageBuffer(DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEAF_LIST, leafList_.handle())
      .storageBuffer(DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEVELS, levels_.handle())
      .storageBuffer(DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_SUMS, attributes.sums.handle())
      .storageImage(DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_VOXELS, attributes.voxels.view())
      .storageBuffer(DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_MOVING, movingLeaves_.handle())
      .push(ctx_, cmd, pipeline);
  const gpu::SvoVoxelAttributesPush pc{depth, uint32_t(attributes.leafCapacity)};
  vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, sizeof(pc), &pc);
  if (step == DYNGI_VOXEL_ATTRIBUTES_STEP_ARGS) vkCmdDispatch(cmd, 1, 1, 1);
  else vkCmdDispatchIndirect(cmd, args.handle(), argsOffset);
  render::computeWriteBarrier(cmd);
}

void SvoBuilder::record(render::FrameContext& frame, const render::Buffer& fragments, const render::Buffer& counters, uint32_t depth,
                        const LeafAttributeTargets* attributes) {
  VkCommandBuffer cmd = frame.cmd;
  counters_ = &counters;
  occupancyIndex_ ^= 1u;  // the last build's pyramid stays readable (previousOccupancy())
  const Buffer& occupancy = occupancy_[occupancyIndex_];
  const bool staticSetChanged = rebuildStaticOccupancy_;
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
      recordMark(cmd, fragments, staticOccupancy_, depth, 0, staticChunks_);
      render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
      rebuildStaticOccupancy_ = false;
    }
    const VkBufferCopy whole{0, 0, occupancy.size()};
    vkCmdCopyBuffer(cmd, staticOccupancy_.handle(), occupancy.handle(), 1, &whole);
    render::computeWriteBarrier(cmd);
    recordMark(cmd, fragments, occupancy, depth, staticChunks_, movingChunks_);
    render::computeWriteBarrier(cmd);
    // 2. Top down, level by level: the occupied nodes get their children, flagged from the pyramid.
    for (uint32_t l = 0; l <= depth; ++l) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, level_.handle());
      DescriptorWrites()
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_LEVELS, levels_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_COUNTERS, svoCounters_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_NODES, nodes_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_NODE_CELLS, nodeCells_.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_OCCUPANCY, occupancy.handle())
          .storageBuffer(DYNGI_SVO_LEVEL_BINDING_LEAF_LIST, leafList_.handle())
          .push(ctx_, cmd, level_);
      const gpu::SvoLevelPush lp{l, depth};
      vkCmdPushConstants(cmd, level_.layout(), kCS, 0, sizeof(lp), &lp);
      vkCmdDispatch(cmd, 1, 1, 1);
      render::computeWriteBarrier(cmd);
      if (l == depth) break;  // leaves: their range is known, they are never subdivided
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, expand_.handle());
      DescriptorWrites()
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_NODES, nodes_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_NODE_CELLS, nodeCells_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_OCCUPANCY, occupancy.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_LEVELS, levels_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_COUNTERS, svoCounters_.handle())
          .storageBuffer(DYNGI_SVO_EXPAND_BINDING_LEAF_LIST, leafList_.handle())
          .push(ctx_, cmd, expand_);
      // The leaf list is for the passes over leaves, which read the leaf attributes (VCT's): without
      // those, the leaves are only counted.
      const gpu::SvoExpandPush ep{l, depth, attributes ? 1u : 0u};
      vkCmdPushConstants(cmd, expand_.layout(), kCS, 0, sizeof(ep), &ep);
      vkCmdDispatchIndirect(cmd, levels_.handle(), VkDeviceSize(l) * sizeof(gpu::SvoLevel) + offsetof(gpu::SvoLevel, dispatch));
      render::computeWriteBarrier(cmd);
    }
    if (attributes) {
      // 3. The voxel attributes (DYNGI_SVO_VOXEL_ATTRIBUTES in gi_gpu_types.h). The voxels the last
      // build's moving leaves touched get back what they held before it; when the static set changed,
      // the image holds the static entities' fragments alone; then the moving entities' (a third of the
      // main job's slots, a tenth of its fragments) are summed and added to their voxels.
      recordVoxelAttributes(cmd, DYNGI_VOXEL_ATTRIBUTES_STEP_RESTORE, depth, *attributes, movingLeaves_, 0);
      render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT);
      vkCmdFillBuffer(cmd, movingLeaves_.handle(), 0, 16, 0);  // no moving leaves yet
      if (staticSetChanged) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, attributes->voxels.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
        render::computeWriteBarrier(cmd);
        recordLeafSums(cmd, fragments, depth, *attributes, 0, staticChunks_, false);
        recordVoxelAttributes(cmd, DYNGI_VOXEL_ATTRIBUTES_STEP_STATIC, depth, *attributes, leafList_, 0);
      }
      render::computeWriteBarrier(cmd);
      recordLeafSums(cmd, fragments, depth, *attributes, staticChunks_, movingChunks_, true);
      recordVoxelAttributes(cmd, DYNGI_VOXEL_ATTRIBUTES_STEP_ARGS, depth, *attributes, movingLeaves_, 0);
      recordVoxelAttributes(cmd, DYNGI_VOXEL_ATTRIBUTES_STEP_MERGE, depth, *attributes, movingLeaves_, 0);
    }
  }
}

void SvoBuilder::fitFirstPool(uint64_t groupBound) {
  if (built_ || groupBound == UINT64_MAX) return;
  // Half over the bound: a build that fills three quarters of the pool grows it (frameFinished).
  const uint64_t want = std::clamp<uint64_t>(groupBound + groupBound / 2, std::min<uint32_t>(kMinNodeGroups, maxNodeGroups_), maxNodeGroups_);
  if (want < nodeGroupCapacity_) resizeNodePool(uint32_t(want), 0);
}

bool SvoBuilder::frameFinished(VoxelStats& stats) {
  built_ = true;
  svoCounters_.invalidateForRead();
  const auto* c = static_cast<const gpu::SvoCounters*>(svoCounters_.mapped());
  uint64_t groups = std::min<uint64_t>(c->groups.x, c->groups.y);
  stats.nodes = groups * 8;
  stats.leaves = c->groups.w;
  levels_.invalidateForRead();
  stats.leafSlots = static_cast<const gpu::SvoLevel*>(levels_.mapped())[depth_].range.y;
  stats.poolOverflow = c->groups.z != 0;
  stats.svoBytes = stats.nodes * 4;
  // The kept static attributes miss the leaves an overflowing build left out: made again next build.
  if (stats.poolOverflow) rebuildStaticOccupancy_ = true;
  if (stats.poolOverflow && nodeGroupCapacity_ >= maxNodeGroups_)
    std::fprintf(stderr, "dyngi: warning: SVO node pool overflow (%u groups); raise maxNodeGroups\n", maxNodeGroups_);
  // Keep the pool between 4/3 and 8 times what the SVO uses: grow before it fills (an overflowing build
  // is conservative: childless nodes count as occupied, so it is rebuilt next frame), shrink after the
  // first build, which had the whole pool.
  uint64_t want = nodeGroupCapacity_;
  if (stats.poolOverflow || groups * 4 > uint64_t(nodeGroupCapacity_) * 3) want = std::max<uint64_t>(2ull * nodeGroupCapacity_, 2 * groups);
  else if (groups * 8 < nodeGroupCapacity_) want = 2 * groups;
  want = std::clamp<uint64_t>(want, std::min<uint32_t>(kMinNodeGroups, maxNodeGroups_), maxNodeGroups_);
  if (want != nodeGroupCapacity_) resizeNodePool(uint32_t(want), groups);
  return stats.poolOverflow && want > groups;  // the conservative SVO stands until the next build
}

uint64_t SvoBuilder::bytes() const { return nodes_.size() + nodeCells_.size() + leafList_.size() + 2 * occupancy_[0].size(); }

void SvoBuilder::resizeNodePool(uint32_t groups, uint64_t keepGroups) {
  vkDeviceWaitIdle(ctx_.device());
  Buffer freshNodes(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  Buffer freshCells(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  Buffer freshLeaves(ctx_, leafListBytes(groups), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, MemoryUsage::GpuOnly,
                     "svo leaf list");
  keepGroups = std::min<uint64_t>(keepGroups, groups);
  // The current SVO stays readable until the next build, which may be many frames away (a still scene):
  // its nodes and their cells (where radiance injection puts each leaf, where the VCT atlas puts each
  // node's texel) both come along.
  if (keepGroups > 0)
    ctx_.immediate([&](VkCommandBuffer cmd) {
      VkBufferCopy copy{0, 0, keepGroups * 8 * 4};
      vkCmdCopyBuffer(cmd, nodes_.handle(), freshNodes.handle(), 1, &copy);
      vkCmdCopyBuffer(cmd, nodeCells_.handle(), freshCells.handle(), 1, &copy);
      // The kept SVO's leaves are nodes of its first keepGroups groups: at most 8 per group.
      const VkBufferCopy leaves{0, 0, leafListBytes(uint32_t(keepGroups))};
      vkCmdCopyBuffer(cmd, leafList_.handle(), freshLeaves.handle(), 1, &leaves);
    });
  nodes_ = std::move(freshNodes);
  nodeCells_ = std::move(freshCells);
  leafList_ = std::move(freshLeaves);
  nodeGroupCapacity_ = groups;
}

}  // namespace dyngi::gi
