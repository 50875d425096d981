#pragma once
// dyngi's CPU ray-tracing scene: an Embree 3 two-level BVH that follows the ECS.
//
// One bottom-level BVH per mesh (built once at high quality for rigid meshes; built for REFIT for
// meshes that deform, e.g. skinned ones), one instance per entity with a MeshInstance. `sync` touches
// only what changed since a tick: moved entities update their instance transform, deformed meshes are
// refit, added/removed entities are attached/detached. Queries: closest hit (entity, primitive,
// barycentrics) and occlusion of segments, one at a time or eight at a time.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/gi/change_set.h"

namespace dyngi::gi {

struct RayHit {
  bool hit = false;
  float t = 0.0f;
  ecs::Entity entity{};
  uint32_t primitive = 0;
  float u = 0.0f, v = 0.0f;       // barycentrics of vertices 1 and 2 (vertex 0 weight = 1 - u - v)
  scene::MeshId mesh = 0;
};

struct Segment {
  glm::vec3 from;
  glm::vec3 to;
};

struct BvhStats {
  size_t instances = 0;
  size_t meshes = 0;
  size_t instancesUpdated = 0;   // transform changes this sync
  size_t instancesAdded = 0;
  size_t instancesRemoved = 0;
  size_t meshesRefit = 0;
  size_t meshesRebuilt = 0;      // bottom-level builds this sync (new or changed topology)
  double updateMs = 0.0;
};

class EmbreeScene {
 public:
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Brings the BVH up to date with everything that changed after `since` (0: everything).
  const BvhStats& sync(const ecs::World& world, const scene::AssetStore& assets, ecs::Tick since);
  // The same from a change set the caller computed (the GI system's one set per frame).
  const BvhStats& sync(const ecs::World& world, const scene::AssetStore& assets, const ChangeSet& changes);
  // Drops everything and builds from scratch (the baseline the incremental path is measured against).
  const BvhStats& rebuild(const ecs::World& world, const scene::AssetStore& assets);
  const BvhStats& stats() const { return stats_; }

  RayHit intersect(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax) const;
  // True when something lies strictly between the segment's ends (ends shrunk by `epsilon`).
  bool occluded(const Segment& s, float epsilon = 1e-4f) const;
  // True when the ray meets something in [tmin, tmax]: the same ray as intersect() with the same
  // arguments, so the two agree exactly (a segment's recomputed direction can graze an edge the ray
  // passed).
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax) const;
  // Occlusion of many segments; out[i] = 1 when occluded. Stream: Embree's ray streams (rtcOccluded1M);
  // Packet8: 8-wide packets (rtcOccluded8), which pay off only for coherent rays.
  enum class BatchMode { Stream, Packet8 };
  void occluded(const Segment* segments, size_t count, uint8_t* out, float epsilon = 1e-4f,
                BatchMode mode = BatchMode::Stream) const;

  glm::mat4 instanceTransform(ecs::Entity e) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  BvhStats stats_;
};

}  // namespace dyngi::gi
