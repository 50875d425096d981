#include "dyngi/gi/gi_system.h"

#include <chrono>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::gi {

GiSystem::GiSystem(render::VulkanContext& ctx, const scene::AssetStore& assets, const GiSettings& s) : assets_(assets), settings_(s) {
  bvh_ = std::make_unique<EmbreeScene>();
  bool needVoxels = s.mode == GiMode::ManyLightsRsm || s.visibility == VisibilityBackend::Svo;
  if (needVoxels) {
    // The VPL techniques march the nodes only; the voxel debug view turns attributes on when asked.
    voxels_ = std::make_unique<VoxelScene>(ctx, VoxelSettings{.resolution = s.svoResolution, .leafAttributes = false});
    voxelSync_ = std::make_unique<VoxelSyncSystem>(*voxels_, assets);
  }
  if (s.mode == GiMode::ManyLightsRsm) {
    ManyLightsSettings ms;
    ms.vplCount = s.vplCount;
    ms.bounces = s.bounces;
    ms.interleave = s.interleave;
    ms.distanceClamp = s.distanceClamp;
    ms.seed = uint32_t(s.seed);
    manyLights_ = std::make_unique<ManyLights>(ctx, *voxels_, ms);
  } else {
    paths_ = std::make_unique<VplPaths>(VplPathSettings{.count = s.vplCount, .bounces = s.bounces, .reshootBudget = s.reshootBudget,
                                                        .temporalSets = s.temporalSets, .seed = s.seed,
                                                        .lightMoveTolerance = s.lightMoveTolerance});
    TemporalSettings ts;
    ts.interleave = s.interleave;
    ts.distanceClamp = s.distanceClamp;
    ts.reprojectionCutoff = s.reprojectionCutoff;
    ts.visibility = s.visibility;
    temporal_ = std::make_unique<TemporalIndirect>(ctx, *paths_, voxels_.get(), bvh_.get(), ts);
  }
}

GiSystem::~GiSystem() = default;

void GiSystem::attach(render::Renderer& renderer) {
  if (voxels_) renderer.addFeature(voxels_.get());
  if (manyLights_) renderer.addFeature(manyLights_.get());
  if (temporal_) renderer.addFeature(temporal_.get());
}

void GiSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  auto t0 = std::chrono::steady_clock::now();
  // 1. What moved or deformed since the last run (change ticks only, no scan of the world).
  std::unordered_set<ecs::Entity> moved;
  world.forEachChanged<scene::WorldTransform>(ctx.lastRun, [&](ecs::Entity e) {
    if (world.has<scene::MeshInstance>(e)) moved.insert(e);
  });
  world.forEachChanged<scene::MeshInstance>(ctx.lastRun, [&](ecs::Entity e) { moved.insert(e); });
  world.each<scene::SkinnedMesh>([&](ecs::Entity e, const scene::SkinnedMesh& sm) {
    uint32_t v = assets_.mesh(sm.deformed).version;
    auto [it, fresh] = meshVersions_.try_emplace(sm.deformed, v);
    if (!fresh && it->second != v) moved.insert(e);
    it->second = v;
  });
  for (ecs::Entity e : world.removedSince<scene::MeshInstance>(ctx.lastRun)) moved.insert(e);
  // 2. BVH: instance transforms, refits, added/removed.
  bvh_->sync(world, assets_, ctx.lastRun);
  // 3. Voxels: mark what must be re-voxelized (the GPU work is recorded by the VoxelScene feature).
  if (voxelSync_) voxelSync_->run(world, ctx);
  // 4-5. VPL invalidation and replacement.
  if (paths_) {
    render::RenderSnapshot snapshot = render::extractSnapshot(world, assets_, ctx.time.frame);
    paths_->update(snapshot, *bvh_, assets_, moved);
  }
  syncMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

GiStats GiSystem::stats() const {
  GiStats s;
  s.bvh = bvh_->stats();
  if (voxels_) s.voxels = voxels_->stats();
  if (paths_) s.vpl = paths_->stats();
  s.syncMs = syncMs_;
  if (temporal_) {
    s.bvhVisibilityMs = temporal_->lastBvhVisibilityMs();
    s.temporalSet = temporal_->lastRenderedSet();
  }
  return s;
}

}  // namespace dyngi::gi
