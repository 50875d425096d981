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
  // 1. What changed since the last run, once, from the change ticks (no scan of the world); every
  //    consumer below reads this one set.
  const ChangeSet changes = changes_.compute(world, assets_, ctx.lastRun);
  // 2. BVH: instance transforms, refits, added/removed.
  bvh_->sync(world, assets_, changes);
  // 3. Voxels: mark what must be re-voxelized (the GPU work is recorded by the VoxelScene feature).
  if (voxelSync_) voxelSync_->apply(changes);
  // 4-5. VPLs: those on a re-coloured surface keep their paths and take the new albedo (and so does
  //      every later bounce); those on a surface that moved or deformed, with their later bounces, are
  //      invalidated; then up to the budget are reshot.
  if (paths_) {
    render::RenderSnapshot snapshot = render::extractSnapshot(world, assets_, ctx.time.frame);
    const std::unordered_set<ecs::Entity> geometry = changes.geometryChanged();
    std::unordered_set<ecs::Entity> recoloured;
    for (ecs::Entity e : changes.materials)
      if (!geometry.count(e)) recoloured.insert(e);
    paths_->refreshMaterials(snapshot, *bvh_, assets_, recoloured);
    paths_->update(snapshot, *bvh_, assets_, geometry);
  }
  syncMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

uint32_t GiSystem::effectiveVplCount() const {
  if (paths_) return paths_->paths() * paths_->bounces();
  if (manyLights_) return manyLights_->vplCount();
  return 0;
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
