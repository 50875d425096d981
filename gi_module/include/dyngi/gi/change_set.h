#pragma once
// What changed in the world since the GI system last ran: computed once a frame from the ECS change
// ticks (no scan of the world) and handed to every consumer, so the BVH sync, the voxel sync and the
// VPL invalidation agree on one answer. A consumer used on its own (BvhSyncSystem, VoxelSyncSystem)
// computes the same set with its own ChangeTracker.
#include <unordered_map>
#include <vector>

#include "dyngi/engine/ecs/entity_map.h"
#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/alpha_cut.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::gi {

struct ChangeSet {
  ecs::Tick since = 0;                          // changes after this tick; 0: the first run, all is new
  // Each list in the change logs' order (consumers that insert into a BVH keep the order they always
  // had), each entity once per list.
  std::vector<ecs::Entity> moved;        // mesh entities whose world transform changed
  std::vector<ecs::Entity> deformed;     // skinned meshes whose deformed vertices changed
  std::vector<ecs::Entity> meshWritten;  // MeshInstance added or written (another mesh, shadow flag)
  std::vector<ecs::Entity> removed;      // MeshInstance removed or entity destroyed
  std::vector<ecs::Entity> materials;    // Material added or written on a mesh entity (base colour, emission, ...)
  // Of those, the ones whose alpha cut changed (mask toggled, cutoff, texture or its transform): to a
  // ray the surface appeared or vanished there, so it counts as geometry too.
  std::vector<ecs::Entity> cutChanged;
  // Lights are not listed: the VPLs compare each light with the state their paths were shot from.

  // Geometry (place, shape or alpha cut): what the BVH must update and what invalidates VPLs. Other
  // material changes apart.
  ecs::EntitySet geometryChanged() const;
  // Adds a later set's changes (each entity once per list): what changed over two runs.
  void merge(const ChangeSet& later);
};

// Computes change sets; remembers the deformed meshes' versions between calls (a skinned mesh changes
// its vertices without any component write).
class ChangeTracker {
 public:
  ChangeSet compute(const ecs::World& world, const scene::AssetStore& assets, ecs::Tick since);

 private:
  std::unordered_map<scene::MeshId, uint32_t> meshVersions_;
  std::unordered_map<ecs::Entity, scene::AlphaCut> cuts_;  // masked mesh entities' cuts as last seen
};

}  // namespace dyngi::gi
