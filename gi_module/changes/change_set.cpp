#include "dyngi/gi/change_set.h"

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::gi {

ecs::EntitySet ChangeSet::geometryChanged() const {
  ecs::EntitySet out;
  out.reserve(moved.size() + deformed.size() + meshWritten.size());
  out.insert(moved.begin(), moved.end());
  out.insert(deformed.begin(), deformed.end());
  out.insert(meshWritten.begin(), meshWritten.end());
  out.insert(removed.begin(), removed.end());
  out.insert(cutChanged.begin(), cutChanged.end());
  return out;
}

ChangeSet ChangeTracker::compute(const ecs::World& world, const scene::AssetStore& assets, ecs::Tick since) {
  ChangeSet c;
  c.since = since;
  world.forEachChanged<scene::WorldTransform>(since, [&](ecs::Entity e) {
    if (world.has<scene::MeshInstance>(e)) c.moved.push_back(e);
  });
  world.forEachChanged<scene::MeshInstance>(since, [&](ecs::Entity e) { c.meshWritten.push_back(e); });
  world.forEachChanged<scene::Material>(since, [&](ecs::Entity e) {
    if (!world.has<scene::MeshInstance>(e)) return;
    c.materials.push_back(e);
    const scene::AlphaCut now = scene::AlphaCut::of(world.get<scene::Material>(e));
    auto it = cuts_.find(e);
    const scene::AlphaCut before = it == cuts_.end() ? scene::AlphaCut{} : it->second;
    if (since > 0 && !(now == before)) c.cutChanged.push_back(e);
    if (now.masked) cuts_[e] = now;
    else if (it != cuts_.end()) cuts_.erase(it);
  });
  c.removed = world.removedSince<scene::MeshInstance>(since);
  for (ecs::Entity e : c.removed) cuts_.erase(e);
  world.each<scene::SkinnedMesh, scene::MeshInstance>([&](ecs::Entity e, const scene::SkinnedMesh& sm, const scene::MeshInstance&) {
    if (sm.deformed >= assets.meshCount()) return;
    const uint32_t v = assets.mesh(sm.deformed).version;
    auto [it, fresh] = meshVersions_.try_emplace(sm.deformed, v);
    if (!fresh && it->second != v) c.deformed.push_back(e);
    it->second = v;
  });
  return c;
}

void ChangeSet::merge(const ChangeSet& later) {
  auto add = [](std::vector<ecs::Entity>& to, const std::vector<ecs::Entity>& from) {
    ecs::EntitySet have;
    have.insert(to.begin(), to.end());
    for (ecs::Entity e : from)
      if (have.insert(e)) to.push_back(e);
  };
  add(moved, later.moved);
  add(deformed, later.deformed);
  add(meshWritten, later.meshWritten);
  add(removed, later.removed);
  add(materials, later.materials);
  add(cutChanged, later.cutChanged);
}

}  // namespace dyngi::gi
