#pragma once
// The GPU voxel scene: per-frame voxelization into voxel fragments and a sparse voxel octree rebuilt
// from them, plugged into the renderer as a RenderFeature ("voxelize", "svo_build" in stats).
//
// Each mesh entity owns a range of the fragment buffer. Only entities marked dirty (moved, deformed,
// added; see VoxelSyncSystem) are re-voxelized into their range; a removed entity's range is emptied.
// Static geometry is therefore voxelized once and cached. The SVO is rebuilt from all ranges whenever
// any range changed, so voxels an object left are gone and the result equals a build from scratch.
#include <memory>
#include <vector>

#include "dyngi/gi/change_set.h"
#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/gi/budget_controller.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/fragment_ranges.h"
#include "dyngi/gi/options.h"
#include "dyngi/gi/voxel.h"

namespace dyngi::gi {

enum class VoxelDebugView { None, Voxels, SvoSteps };

// A box of voxels of the volume, both corners included.
struct VoxelBox {
  glm::uvec3 min{0u}, max{0u};
  uint64_t voxels() const { return uint64_t(max.x - min.x + 1) * (max.y - min.y + 1) * (max.z - min.z + 1); }
};

struct VoxelSettings {
  uint32_t resolution = 128;       // power of two, 64..512
  float padding = 0.05f;           // volume = scene bounds grown by this fraction per side
  // Metres around the camera the volume covers in a scene wider than that (camera_focus.h): a cube
  // around a focus near the camera, moved in steps of kWindowStep of it, instead of the scene's bounds. 0: the scene.
  float reach = 64.0f;
  uint32_t maxNodeGroups = 1u << 20;  // SVO pool limit: 8 nodes (32 bytes) per group; the pool follows use
  VoxelDebugView debugView = VoxelDebugView::None;  // replaces the final image when set
  // Per-voxel averaged albedo, normal and emission (the voxel debug view, radiance injection). Off, the
  // build makes only what visibility needs: no attribute pass, no attribute memory.
  bool leafAttributes = true;

  static const OptionTable<VoxelSettings>& table();  // resolution and reach: the rest is the host's business
};

struct VoxelStats {
  uint32_t entitiesVoxelized = 0;    // this frame
  uint64_t fragments = 0;            // voxel fragments currently stored (all entities)
  uint64_t fragmentCapacity = 0;
  uint64_t nodes = 0;                // SVO nodes allocated (8 per group)
  uint64_t leaves = 0;               // occupied voxels
  uint64_t leafSlots = 0;            // the SVO's leaf level: eight per group, empty siblings included
  uint64_t svoBytes = 0;             // node pool bytes in use
  uint64_t totalBytes = 0;           // fragments + nodes + attributes, allocated
  uint32_t overflowedEntities = 0;   // re-voxelized next frame with a larger range
  uint32_t entitiesDeferred = 0;     // changed entities the voxelization cap left for a later frame
  uint32_t drawsComputeVoxelized = 0;  // of the last frame that voxelized: draws of small triangles, by compute
  bool poolOverflow = false;         // SVO pool too small (occupancy then conservative)
  bool windowed = false;             // the volume covers the camera's surroundings (VoxelSettings::reach), not the scene
  uint32_t volumeMoves = 0;          // times the window moved with the camera (each a voxelization afresh)
  // Geometry outside the volume is clipped (not voxelized): no error, and no count either.
  bool rebuilt = false;              // the SVO was rebuilt this frame
  // Of this frame's build: slots the mark pass read (the moving entities', plus the static ones' when
  // the static occupancy was rebuilt) and entities the static occupancy holds.
  uint64_t slotsMarked = 0;
  uint32_t staticEntities = 0;
};

class VoxelScene final : public render::RenderFeature {
 public:
  VoxelScene(render::VulkanContext& ctx, const VoxelSettings& settings = {});
  ~VoxelScene() override;

  const char* name() const override { return "voxels"; }
  // The GPU sections it times (stats' stages_ms).
  static std::vector<const char*> timedSections() { return {"voxelize", "svo_build"}; }
  void prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) override;
  bool record(render::FrameContext& frame) override;
  void frameFinished(render::VulkanContext& ctx) override;
  void recordAfterLighting(render::FrameContext& frame) override;

  // Change tracking (called by VoxelSyncSystem, or by hand).
  void markDirty(ecs::Entity e) {
    if (allDirty_) return;  // the next update voxelizes every draw (a first frame's 200,000 marks: 9 MB)
    dirty_.insert(e);
    dirtySince_.emplace(e, frameIndex_);
  }
  void markRemoved(ecs::Entity e) { removed_.insert(e); }
  void markAllDirty() { allDirty_ = true; }
  // Fixes the volume (otherwise the first snapshot's bounds decide it, or in a scene wider than the
  // reach the camera's surroundings, frame by frame). Re-voxelizes everything.
  void setVolume(const VoxelVolume& v);
  void setDebugView(VoxelDebugView v);
  // Builds the leaf attributes from now on (a technique that reads them: radiance injection).
  void enableLeafAttributes();

  // Voxel updates (re-voxelization, the SVO's rebuild) on one frame in `interval` only, what changed in
  // between gathered for that frame: a GI budget's knob (voxelUpdateKnob). Its cost is lag: a moving
  // object's voxels trail it by up to interval - 1 frames. The first frame and a full re-voxelization
  // are never put off.
  void setUpdateInterval(uint32_t interval) { updateInterval_ = std::max(1u, interval); }
  uint32_t updateInterval() const { return updateInterval_; }
  // Whether this frame may update the voxels (prepare): what a technique whose voxel data follows the
  // voxels' (VCT's radiance) refreshes on.
  bool updatesThisFrame() const { return updatesThisFrame_; }
  // The budget's knob over it: the fraction of frames that update (1, 1/2, 1/4).
  QualityKnob updateFractionKnob();
  // A cap on the fragments (as estimated) re-voxelized in one frame, so that a big change (many objects
  // moved at once) is spread over frames: the entities that have waited longest go first, at least one
  // a frame, and the rest keep their old voxels until their turn. `fragments` 0: no cap; `spread`: a GI
  // budget's cap, a quarter of the stored fragments (at least kMinSpreadFragments). The first frame and
  // a new volume are never capped.
  void setVoxelizeCap(uint64_t fragments) { voxelizeCap_ = fragments; }
  void setSpreadVoxelization(bool spread) { spreadVoxelization_ = spread; }
  static constexpr uint64_t kMinSpreadFragments = 1u << 16;
  // The window around the camera (VoxelSettings::reach) moves in steps of this fraction of the reach:
  // each move voxelizes it afresh, and what the camera sees near a side changes at each, so small steps
  // keep the camera near the centre and each step's change small.
  static constexpr float kWindowStep = 0.125f;
  // Draws whose triangles all span at most this many voxels a side (and no normal texture) are voxelized
  // by a compute pass, an invocation a triangle testing its box's few voxels, instead of a geometry-
  // shader quad and its pixels each: the same fragments for far less work with many small instances.
  static constexpr float kComputeVoxelizeSpan = 2.0f;
  // Off: every draw takes the raster voxelizer (to compare the two).
  void setComputeVoxelization(bool on) { computeVoxelization_ = on; }
  // The compute voxelizer's dispatches for `instances` instances of a `triangles`-triangle mesh: 64
  // invocations a group, at most limit.x by limit.y groups each and under 2^31 invocations (the shader's
  // index), a whole number of instances each.
  struct ComputeVoxelizeDispatch {
    uint32_t firstInstance = 0, instanceCount = 0;
    glm::uvec2 groups{0};
  };
  static std::vector<ComputeVoxelizeDispatch> splitComputeVoxelize(uint32_t instances, uint32_t triangles, glm::uvec2 limit);
  // Workgroups a compute-voxelizer dispatch may take (0: the device's maxComputeWorkGroupCount).
  void setComputeDispatchLimit(glm::uvec2 groups) { computeDispatchLimit_ = groups; }
  glm::uvec2 computeDispatchLimit() const;

  const VoxelVolume& volume() const { return volume_; }
  bool hasVolume() const { return haveVolume_; }
  const VoxelStats& stats() const { return stats_; }
  const VoxelSettings& settings() const { return settings_; }

  // GPU buffers for other stages (visibility march, debug view, cone tracing later).
  const render::Buffer& nodes() const;
  // Each occupied voxel's mean albedo, normal and emission (DYNGI_SVO_VOXEL_ATTRIBUTES in gi_gpu_types.h,
  // read through voxel/shaders/leaf_attributes.glsl): an rgba32ui 3D image over the volume, 16 bytes a
  // voxel, in VK_IMAGE_LAYOUT_GENERAL; one texel while the leaf attributes are off.
  const render::Image& voxelAttributes() const { return voxelAttributes_; }
  const render::Buffer& levels() const;
  // Per group of 8 sibling nodes (leaves included), at the group's first slot: its first child's cell's
  // Morton code at its level; sibling c's is that plus c (SVO_NODE_CELL in svo_morton.glsl), the root's 0.
  const render::Buffer& nodeCells() const;
  // The occupied leaves, compacted: (node index, cell) pairs after a header of DYNGI_SVO_LEAF_LIST_HEADER uints
  // (indirect dispatch args, count). What passes over the leaves walk; built with the leaf attributes
  // (enableLeafAttributes), whose readers they are.
  const render::Buffer& leafList() const;
  // The occupancy pyramid (a bit a cell of every level, DYNGI_SVO_LEVEL_BASE) of the last SVO build and
  // of the build before it: a cell set in the one before and clear in the last has emptied. Valid after
  // the second build; stats().rebuilt says whether this frame built.
  const render::Buffer& occupancy() const;
  const render::Buffer& previousOccupancy() const;
  // The leaf attributes' capacity in leaves (a leaf index at or past it has none).
  uint64_t leafCapacity() const { return attributeLeaves_; }

  // Where voxels may have been emptied this frame: the boxes the re-voxelized and removed entities
  // covered at their last voxelization (their bounds and a voxel of margin), or everywhere when the
  // whole volume was voxelized afresh (the first frame, a new volume). A consumer that keeps per-voxel
  // state (VCT's radiance volumes) clears these instead of the whole volume.
  const std::vector<VoxelBox>& staleBoxes() const { return staleBoxes_; }
  bool staleEverywhere() const { return staleEverywhere_; }
  // The boxes the entities voxelized this frame cover now (bounds and a voxel of margin): with the stale
  // boxes, everywhere a voxel may have been filled, emptied or given new attributes by this frame's build.
  // Both lists are empty when staleEverywhere(): every voxel may have changed.
  const std::vector<VoxelBox>& freshBoxes() const { return freshBoxes_; }
  // Some stored fragment emits (an entity voxelized with an emissive material): the passes over the
  // leaf attributes leave emission out otherwise.
  bool fragmentsEmit() const { return !emittingEntities_.empty(); }

 private:
  friend class VoxelProbe;  // tests' and tools' read-backs (gi_module/testing)
  using Range = FragmentRange;
  // The dirty entities this frame's voxelization cap leaves for later (empty without a cap).
  ecs::EntitySet deferredByCap(const render::RenderSnapshot& snapshot, const glm::mat4& toVoxel) const;
  // Fragment storage of `slots` slots at least; kept fragments are copied, nothing is re-voxelized.
  void ensureCapacity(uint64_t slots);
  // What the entities' voxel boxes allow the SVO: its leaf slots and node groups (UINT64_MAX: unknown).
  struct OccupancyBound {
    uint64_t leafSlots = UINT64_MAX, nodeGroups = UINT64_MAX;
  };
  OccupancyBound occupancyBound() const;
  // Moves every range's fragments into a buffer sized by what they hold (FragmentRanges::compact).
  void compactFragments();
  void reallocateFragments(uint64_t slots, const std::vector<SlotCopy>& keep);
  void allocateAttributes(uint64_t leafSlots);  // leafSlots 0: none

  render::VulkanContext& ctx_;
  VoxelSettings settings_;
  VoxelVolume volume_;
  bool haveVolume_ = false;
  bool volumeFixed_ = false;  // by setVolume: no window follows the camera
  // The volume for this snapshot: the scene's bounds (decided once) or the window around the camera.
  void placeVolume(const render::RenderSnapshot& snapshot);
  bool allDirty_ = true;
  uint32_t updateInterval_ = 1;
  uint64_t voxelizeCap_ = 0;
  bool spreadVoxelization_ = false;
  ecs::EntityMap<uint64_t> dirtySince_;  // the frame each dirty entity changed first
  bool updatesThisFrame_ = true;
  ecs::EntitySet dirty_, removed_;
  FragmentRanges ranges_;  // where each entity's fragments live in fragments_
  std::unique_ptr<class SvoBuilder> svo_;  // the SVO over fragments_ (voxel/svo_builder.h)

  // What this frame records (decided in prepare).
  std::vector<size_t> drawsToVoxelize_;   // indices into snapshot.draws
  std::vector<size_t> rasterDraws_, computeDraws_;  // drawsToVoxelize_ by voxelizer
  bool computeVoxelization_ = true;
  glm::uvec2 computeDispatchLimit_{0};
  std::vector<Range> rangesToEmpty_;
  bool rebuildSvo_ = false;
  bool storageMoved_ = false;  // fragments were moved or the derived buffers reallocated: rebuild the SVO
  std::vector<ecs::Entity> voxelizedThisFrame_;
  ecs::EntityMap<VoxelBox> voxelBoxes_;  // each entity's box at its last voxelization
  std::vector<VoxelBox> staleBoxes_, freshBoxes_;
  ecs::EntitySet emittingEntities_;  // voxelized with an emissive material
  bool staleEverywhere_ = false;

  render::Buffer fragments_, counters_;
  render::Buffer voxelizeRanges_;  // gpu::VoxelizeRange per FrameInstances slot (host-visible)
  render::Buffer attributes_;  // the leaf sums a build makes (scratch, zero between builds): DYNGI_LEAF_* in gi_gpu_types.h
  render::Image voxelAttributes_;
  uint64_t attributeLeaves_ = 0;  // leaf slots the attribute buffer holds
  uint64_t frameIndex_ = 0;
  // One voxelize pipeline per material kind (base-colour / emissive texture or not), made on first use:
  // lavapipe would run the texture lookups of a branch not taken.
  render::Pipeline voxelize_[32];  // by the material's texture bits it reads (DYNGI_MATERIAL_*_TEX), + 8: alpha-masked, + 16: a normal texture
  render::Pipeline& voxelizePipelineFor(uint32_t textureBits);
  render::Pipeline voxelizeSmall_[16];  // the compute voxelizer, by the same bits (no normal texture)
  render::Pipeline& voxelizeSmallPipelineFor(uint32_t textureBits);
  bool voxelizesByCompute(const render::RenderSnapshot& snapshot, const render::DrawItem& d, const FragmentRanges::Estimate& estimate) const;
  void writeVoxelizeRanges(const render::FrameContext& frame);
  std::unique_ptr<class VoxelDebugPass> debugPass_;  // voxel/voxel_debug_pass.h
  VoxelStats stats_;
};

// Marks moved, deformed, added and removed mesh entities dirty in a VoxelScene (change ticks only).
class VoxelSyncSystem final : public ecs::System {
 public:
  VoxelSyncSystem(VoxelScene& voxels, const scene::AssetStore& assets) : voxels_(voxels), assets_(assets) {}
  const char* name() const override { return "voxel_sync"; }
  // On its own: computes what changed since its last run, then apply().
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
  // Marks what `changes` says must be re-voxelized (moved, deformed, re-meshed, re-coloured) or dropped.
  void apply(const ChangeSet& changes);

 private:
  VoxelScene& voxels_;
  const scene::AssetStore& assets_;
  ChangeTracker tracker_;
};

}  // namespace dyngi::gi
