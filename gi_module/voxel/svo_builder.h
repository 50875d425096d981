#pragma once
// The sparse voxel octree over the voxel scene's fragments, rebuilt on the GPU when they change
// ("svo_build" in stats): every fragment marks its cells in an occupancy pyramid (the static
// entities' kept in a pyramid of their own that each build copies, so only moving entities are marked
// every time), then top-down level passes give the occupied nodes their children, then, when asked,
// the leaves get averaged attributes. The node pool follows what the SVO uses. VoxelScene owns one.
#include <cstdint>
#include <vector>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/resources.h"
#include "dyngi/gi/fragment_ranges.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

// Where a build puts the voxels' attributes (VoxelScene owns both).
struct LeafAttributeTargets {
  const render::Buffer& sums;    // per leaf slot: a build's sums (DYNGI_LEAF_* in gi_gpu_types.h), zero between builds
  uint64_t leafCapacity;         // leaf slots `sums` holds
  const render::Image& voxels;   // the voxel attributes image (DYNGI_SVO_VOXEL_ATTRIBUTES), layout GENERAL
  bool emission;                 // some fragment emits: the emission sums too
};

class SvoBuilder {
 public:
  SvoBuilder(render::VulkanContext& ctx, uint32_t resolution, uint32_t maxNodeGroups);
  // Before a build (prepare): which entities the static pyramid holds and the mark work, cut into
  // workgroup-sized chunks of the ranges. `voxelized` and `removed`: this frame's.
  void plan(const FragmentRanges& ranges, uint64_t frame, const std::vector<ecs::Entity>& voxelized, const std::vector<ecs::Entity>& removed,
            VoxelStats& stats);
  // Before the first build: the pool cut to `groupBound` node groups, an upper bound on what the build
  // needs (VoxelScene's from the voxel boxes), instead of the full tree's.
  void fitFirstPool(uint64_t groupBound);
  bool built() const { return built_; }  // a build has finished (frameFinished)
  uint32_t nodeGroupCapacity() const { return nodeGroupCapacity_; }
  // Everything is voxelized again: the static pyramid is rebuilt at the next build.
  void invalidateStaticOccupancy() { rebuildStaticOccupancy_ = true; }
  // Records the build over `fragments`; with `attributes`, the voxel attributes too: when the static set
  // changed, the static entities' fragments summed and written to their voxels; in every build, the
  // voxels the last build's moving leaves touched restored, and the moving entities' fragments summed
  // and added to their voxels.
  // `counters`: the voxelizer's fragment counter of each range (the chunks' ends, DYNGI_SVO_CHUNK).
  void record(render::FrameContext& frame, const render::Buffer& fragments, const render::Buffer& counters, uint32_t depth,
              const LeafAttributeTargets* attributes);
  // After the build's frame: node and leaf counts into `stats`, the pool resized to follow use. True
  // when the pool overflowed and grew: build again next frame.
  bool frameFinished(VoxelStats& stats);

  const render::Buffer& nodes() const { return nodes_; }
  const render::Buffer& levels() const { return levels_; }
  const render::Buffer& nodeCells() const { return nodeCells_; }
  // The occupied leaves (node index, cell), compacted (DYNGI_SVO_LEAF_LIST_HEADER in gi_gpu_types.h).
  const render::Buffer& leafList() const { return leafList_; }
  // The occupancy pyramid (DYNGI_SVO_LEVEL_BASE) of the last build, and of the build before it: where
  // both differ, cells emptied (VCT zeroes its per-voxel state there).
  const render::Buffer& occupancy() const { return occupancy_[occupancyIndex_]; }
  const render::Buffer& previousOccupancy() const { return occupancy_[occupancyIndex_ ^ 1u]; }
  render::Buffer& counters() { return svoCounters_; }
  uint64_t bytes() const;  // nodes, node cells, the leaf list and the occupancy pyramids

 private:
  // Records the mark pass over chunks [firstChunk, firstChunk + chunkCount) into `target`.
  void recordMark(VkCommandBuffer cmd, const render::Buffer& fragments, const render::Buffer& target, uint32_t depth, uint32_t firstChunk,
                  uint32_t chunkCount);
  // Sums the fragments of chunks [firstChunk, firstChunk + chunkCount) into the leaf sums (zero before);
  // `listLeaves`: each leaf into the moving leaves.
  void recordLeafSums(VkCommandBuffer cmd, const render::Buffer& fragments, uint32_t depth, const LeafAttributeTargets& attributes,
                      uint32_t firstChunk, uint32_t chunkCount, bool listLeaves);
  // One step of svo_voxel_attributes.comp (DYNGI_VOXEL_ATTRIBUTES_STEP_*), dispatched indirectly from
  // `args` at `argsOffset` (or one invocation for the args step).
  void recordVoxelAttributes(VkCommandBuffer cmd, uint32_t step, uint32_t depth, const LeafAttributeTargets& attributes,
                             const render::Buffer& args, VkDeviceSize argsOffset);
  void resizeNodePool(uint32_t groups, uint64_t keepGroups);

  render::VulkanContext& ctx_;
  uint32_t maxNodeGroups_;
  uint32_t nodeGroupCapacity_ = 0;
  bool built_ = false;
  render::Buffer nodes_, levels_, svoCounters_;
  render::Buffer nodeCells_;  // per group of 8 nodes (leaves included), at its first slot: the first child's Morton code
                              // (svo_expand.comp; SVO_NODE_CELL derives the siblings'), sized like nodes_
  render::Buffer leafList_;   // the occupied leaves (node index, cell) after a header (svo_expand.comp, svo_level.comp)
  render::Buffer occupancy_[2];  // occupancy pyramid of every level (svo_mark.comp), by build: the last one's at occupancyIndex_
  uint32_t occupancyIndex_ = 0;
  // The pyramid of the entities in staticEntities_ alone: a build starts from a copy of it and marks the
  // moving entities' fragments only. Rebuilt when one of them moves or is removed, or when a moving
  // entity has settled and can join; so are their voxel attributes.
  render::Buffer staticOccupancy_;
  ecs::EntitySet staticEntities_;
  uint32_t depth_ = 0;  // of the leaf level
  bool rebuildStaticOccupancy_ = true;
  render::Buffer markChunks_;                     // DYNGI_SVO_CHUNK per mark workgroup
  const render::Buffer* counters_ = nullptr;      // the build being recorded's (record())
  uint32_t staticChunks_ = 0, movingChunks_ = 0;  // this frame's: the static ones first
  // The moving leaves of the last build (DYNGI_SVO_VOXEL_ATTRIBUTES in gi_gpu_types.h): room for one a
  // slot of the moving entities' ranges.
  render::Buffer movingLeaves_;
  render::Pipeline mark_, level_, expand_;
  // Made on first use: only builds with leaf attributes run them.
  render::LazyPipeline leafAttributes_[2];   // [1]: with the emission sums
  render::LazyPipeline voxelAttributes_[4];  // by step (DYNGI_VOXEL_ATTRIBUTES_STEP_*)
};

}  // namespace dyngi::gi
