#pragma once
// Where each entity's voxel fragments live in the voxel scene's fragment buffer: one contiguous range of
// slots per entity and the counter its fragments are appended with. CPU bookkeeping only: VoxelScene
// owns the GPU buffers and carries out the fills and copies this plans. Sized by an estimate the first
// time, then by the count the voxelizer wrote; compacted when the ranges hold twice what they need.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/entity_map.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::gi {

struct FragmentRange {
  uint64_t first = 0, capacity = 0;  // slots
  uint64_t lastEstimate = 0;         // estimateFragments() when it was last voxelized (lastCount's pose)
  uint64_t lastVoxelizedFrame = 0;
  uint32_t counter = 0;              // index into the counters buffer
  uint32_t lastCount = 0;            // fragments written (read back after the frame)
  uint32_t voxelizations = 0;        // how often the entity was voxelized (more than once: it moves)
  bool written = false;
};

// Kept fragments to move, in slots.
struct SlotCopy {
  uint64_t from = 0, to = 0, count = 0;
};

class FragmentRanges {
 public:
  // Moving: voxelized again (after its first time) within the last kSettleFrames frames.
  static constexpr uint64_t kSettleFrames = 60;
  // Below this many slots the buffer is never compacted.
  static constexpr uint64_t kMinCompactSlots = 1u << 16;
  static bool isMoving(const FragmentRange& r, uint64_t frame) {
    return r.voxelizations > 1 && frame - r.lastVoxelizedFrame < kSettleFrames;
  }
  // What a moving entity keeps: its count changes as it turns.
  static uint64_t movingCapacity(const FragmentRange& r) { return 2 * uint64_t(r.lastCount) + 64; }
  // An upper estimate of the fragments `mesh` writes under `modelToVoxel` (overshoots are caught after
  // the frame, from the counts), within a volume of `resolution`^3 voxels (0: unbounded): what lies
  // outside a window around the camera reserves nothing.
  static uint64_t estimateFragments(const scene::MeshData& mesh, const glm::mat4& modelToVoxel, uint32_t resolution = 0) {
    return estimate(mesh, modelToVoxel, resolution).fragments;
  }
  struct Estimate {
    uint64_t fragments = 0;
    float widestTriangle = 0;  // the largest side of a triangle's box, voxels (+inf: not finite)
  };
  static Estimate estimate(const scene::MeshData& mesh, const glm::mat4& modelToVoxel, uint32_t resolution = 0);

  // Forgets every range (a new volume: everything is voxelized again).
  void clear();
  void reserve(size_t entities) { ranges_.reserve(entities); }
  // Drops `e`'s range and frees its counter; returns the range, whose slots must be emptied.
  std::optional<FragmentRange> remove(ecs::Entity e);
  // `e`'s range for this frame's voxelization of `estimate` fragments: its own while it holds what it
  // needs, else a fresh one at `highWater` (advanced; the old one is appended to `toEmpty`). Not stored
  // until commit(); highWater() moves only with setHighWater().
  FragmentRange plan(ecs::Entity e, uint64_t estimate, uint64_t& highWater, std::vector<FragmentRange>& toEmpty);
  void commit(ecs::Entity e, FragmentRange r, uint64_t frame);
  // True when the ranges hold more than twice what they need (counts from the last frame).
  bool wantsCompaction() const;
  // Packs every range from slot 0 (static entities keep exactly their fragments, moving ones their
  // slack) and returns the copies that keep their fragments; highWater() becomes the packed end.
  std::vector<SlotCopy> compact();

  uint64_t highWater() const { return highWater_; }  // slots in use or planned, from 0
  void setHighWater(uint64_t slots) { highWater_ = slots; }
  uint32_t counterCount() const { return counterCount_; }
  uint64_t storedFragments() const;  // fragments written, over all ranges
  const ecs::EntityMap<FragmentRange>& all() const { return ranges_; }
  FragmentRange& at(ecs::Entity e) { return ranges_.at(e); }
  const FragmentRange& at(ecs::Entity e) const { return ranges_.at(e); }

 private:
  // Slots for an entity about to be voxelized: it keeps its range while it holds `minimum`; a new one
  // gets `fresh`.
  struct Need {
    uint64_t minimum, fresh;
  };
  static Need need(uint64_t estimate, const FragmentRange* previous);

  ecs::EntityMap<FragmentRange> ranges_;
  std::vector<uint32_t> freeCounters_;
  uint32_t counterCount_ = 0;
  uint64_t highWater_ = 0;
};

}  // namespace dyngi::gi
