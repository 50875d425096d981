#pragma once
// dyngi's GI as one ECS system plus render features. A host adds it in a few lines:
//
//   auto gi = std::make_unique<dyngi::gi::GiSystem>(vulkan, assets, settings);
//   gi->attach(renderer);                                           // its render features
//   scheduler.add(dyngi::ecs::Phase::PostUpdate, std::move(gi));    // after transforms and skinning
//
// Per frame (run): collect what moved or deformed since the last run (change ticks) -> BVH update ->
// voxel/SVO update (dirty entities) -> VPL invalidation -> replacement; the render features then pick
// the temporal set, gather, reproject and filter. Nothing in engine/ knows about any of this.
#include <memory>
#include <unordered_map>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/gi/change_set.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/many_lights.h"
#include "dyngi/gi/temporal_indirect.h"
#include "dyngi/gi/voxel_scene.h"
#include "dyngi/gi/vpl_paths.h"

namespace dyngi::gi {

enum class GiMode {
  ManyLightsRsm,  // VPLs sampled from reflective shadow maps every frame (SVO visibility)
  Temporal,       // incremental VPL paths, temporal sets, reprojection (SVO or BVH visibility)
};

struct GiSettings {
  GiMode mode = GiMode::Temporal;
  VisibilityBackend visibility = VisibilityBackend::Svo;
  uint32_t vplCount = 512;
  uint32_t bounces = 1;
  uint32_t temporalSets = 16;     // T
  uint32_t reshootBudget = 0;     // 0: vplCount / T per frame (one set's worth: steady frame time)
  uint32_t interleave = 4;        // K
  float distanceClamp = 0.01f;    // B (world units^2)
  uint32_t svoResolution = 128;
  float reprojectionCutoff = 0.02f;
  float lightMoveTolerance = 0.02f;  // see VplPathSettings
  uint64_t seed = 1;
};

struct GiStats {
  BvhStats bvh;
  VoxelStats voxels;
  VplPathStats vpl;
  double syncMs = 0;           // the whole CPU side of run()
  double bvhVisibilityMs = 0;  // Embree visibility of the last frame (BVH backend)
  uint32_t temporalSet = 0;    // the set gathered last frame
};

class GiSystem final : public ecs::System {
 public:
  GiSystem(render::VulkanContext& ctx, const scene::AssetStore& assets, const GiSettings& settings = {});
  ~GiSystem() override;
  const char* name() const override { return "gi"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
  // Adds the render features (voxel scene, then the technique) to the renderer.
  void attach(render::Renderer& renderer);

  const GiSettings& settings() const { return settings_; }
  GiStats stats() const;
  EmbreeScene& bvh() { return *bvh_; }
  VoxelScene* voxels() { return voxels_.get(); }
  VplPaths* paths() { return paths_.get(); }
  TemporalIndirect* temporal() { return temporal_.get(); }
  ManyLights* manyLights() { return manyLights_.get(); }
  // The VPL count the technique uses: GiSettings::vplCount rounded down to a multiple of the bounces
  // (each path or RSM bounce level holds the same number).
  uint32_t effectiveVplCount() const;

 private:
  const scene::AssetStore& assets_;
  GiSettings settings_;
  std::unique_ptr<EmbreeScene> bvh_;
  std::unique_ptr<VoxelScene> voxels_;
  std::unique_ptr<VoxelSyncSystem> voxelSync_;
  std::unique_ptr<VplPaths> paths_;
  std::unique_ptr<TemporalIndirect> temporal_;
  std::unique_ptr<ManyLights> manyLights_;
  ChangeTracker changes_;  // the one change set per frame
  double syncMs_ = 0;
};

}  // namespace dyngi::gi
