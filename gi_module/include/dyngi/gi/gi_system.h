#pragma once
// dyngi's GI as one ECS system plus render features. A host adds it in a few lines:
//
//   auto gi = std::make_unique<dyngi::gi::GiSystem>(vulkan, assets, settings);
//   gi->attach(renderer);                                           // its render features
//   scheduler.add(dyngi::ecs::Phase::PostUpdate, std::move(gi));    // after transforms and skinning
//
// Per frame, in run() (ECS): what changed since the last run (one ChangeSet) -> BVH update -> voxel
// dirty marks. Then, when the renderer prepares the frame, with the one snapshot it renders (no second
// extraction): the technique's CPU work (VPL invalidation and replacement) with the change set, then
// the render features record the voxel update and the technique's passes. The technique is chosen by
// name from the registry (technique.h); nothing in engine/ knows about any of this.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/gi/budget_controller.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/change_set.h"
#include "dyngi/gi/gi_settings.h"
#include "dyngi/gi/technique.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

class GiIndirectView;

// The GI system's own figures; a technique's are its statsSections() and cpuMs().
struct GiStats {
  BvhStats bvh;
  VoxelStats voxels;
  double syncMs = 0;           // the whole CPU side of run()
  // The GI's cost of the last frame rendered: its GPU sections (voxel scene and technique) plus the
  // technique's CPU sections (cpuMs); what a GI budget holds. -1 before the first timed frame.
  double giMs = -1;
  // What the budget reads: "timestamps", or "fenced" when a fenced check frame found that the device's
  // timestamps miss part of the GI's work (lavapipe's miss compute passes) or the renderer was fenced
  // from the start; empty until a budget has a verdict.
  std::string budgetTiming;
  double timestampCoverage = -1;  // the timestamped GI cost over the fenced check frame's (1: they bracket all of it)
};

class GiSystem final : public ecs::System {
 public:
  // Throws std::invalid_argument for a technique name the registry does not know.
  GiSystem(render::VulkanContext& ctx, const scene::AssetStore& assets, const GiSettings& settings = {});
  ~GiSystem() override;
  const char* name() const override { return "gi"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override;
  // Adds the render features (voxel scene, then the technique's) to the renderer.
  void attach(render::Renderer& renderer);
  // Takes its features out of the renderer (GI off at run time: lighting then gets no indirect light)
  // and stops following the world; attach() later starts over from the whole world.
  void detach();
  bool attached() const { return renderer_ != nullptr; }
  // Switches the technique or any setting at run time (between frames): the GI starts over as if it had
  // been made with `settings`. Its BVH, voxel scene and technique are rebuilt from the whole world on the
  // next run, and its features in the attached renderer are replaced. Throws std::invalid_argument for
  // an unknown technique; nothing changes then.
  void reset(const GiSettings& settings);

  const GiSettings& settings() const { return settings_; }
  Technique& technique() { return *technique_; }
  const TechniqueEntry& techniqueEntry() const { return *entry_; }
  GiStats stats() const;
  EmbreeScene* bvh() { return bvh_.get(); }  // null when the technique traces no rays on the CPU
  VoxelScene* voxels() { return voxels_.get(); }
  // The views of this GI: "final" and "indirect" (every technique's), then the technique's own.
  std::vector<std::string> debugViews() const;
  // Switches to one of debugViews(); false (and no change) for a name it does not have.
  bool setDebugView(std::string_view name);
  // The GI budget's controller, when GiSettings::budget asks for one.
  const BudgetController* budget() const { return budget_.get(); }
  // Sets the GI budget while it runs (settings().budget follows): a controller is made at the
  // technique's full quality when there was none, and 0 removes it, the knobs back at full quality.
  void setBudgetMs(double budgetMs);
  // A GI budget reads timestamps only while they bracket this share of a fenced frame's GI cost (within
  // 15 percent of what the device spends); fenced frames otherwise (GiStats::budgetTiming).
  static constexpr double kMinTimestampCoverage = 0.85;
  // Every GPU section the GI times: the voxel scene's (when it has one) and the technique's.
  std::vector<const char*> timedSections() const;

 private:
  friend class GiFrameUpdate;
  // The technique's CPU work on the renderer's snapshot, with every change since the last such call.
  void updateTechnique(const render::RenderSnapshot& snapshot);
  // After the frame's fence: its GI cost (GiStats::giMs) to the budget controller, whose knob changes
  // apply from the next frame.
  void frameTimed();
  double measureLastFrame() const;  // the GI's cost in the renderer's last timed frame, or -1
  // The GI's cost from a frame's pass times: its sections plus the technique's CPU sections; -1 if none.
  double giCost(const std::vector<std::pair<std::string, double>>& gpuMs) const;
  void checkTiming(bool oneOffFrame);  // frameTimed(): whether the budget can read timestamps

  // Makes the BVH, voxel scene, technique and budget for `settings` (the constructor and reset()).
  void build(const GiSettings& settings);
  // While a budget holds: the technique's one-off work and a big re-voxelization spread over frames.
  void spreadOneOffWork(bool spread);
  void addFeaturesTo(render::Renderer& renderer);
  void removeFeaturesFrom(render::Renderer& renderer);

  render::VulkanContext& ctx_;
  const scene::AssetStore& assets_;
  GiSettings settings_;
  bool startOver_ = false;  // reset(): the next run sees the whole world as new
  bool detached_ = false;   // detach(): no features in any renderer, run() does nothing
  const TechniqueEntry* entry_ = nullptr;
  std::unique_ptr<EmbreeScene> bvh_;
  std::unique_ptr<VoxelScene> voxels_;
  std::unique_ptr<VoxelSyncSystem> voxelSync_;
  std::unique_ptr<Technique> technique_;
  std::unique_ptr<render::RenderFeature> frameUpdate_;  // attached first: calls updateTechnique
  std::unique_ptr<GiIndirectView> indirectView_;        // attached last: the `indirect` view
  std::string view_ = "final";
  render::Renderer* renderer_ = nullptr;                 // whose timings the budget reads; reset() swaps features in it
  std::unique_ptr<BudgetController> budget_;
  double giMs_ = -1;
  // The budget's timing check (checkTiming): a few fenced frames now and then, timestamps beside them.
  struct TimingCheck {
    static constexpr uint32_t kWarmupFrames = 4;   // timed frames (not one-off) before the first check
    static constexpr uint32_t kFencedFrames = 3;   // frames a check fences
    static constexpr uint32_t kCheckEvery = 300;   // timed frames between checks while the timestamps hold
    uint64_t framesSeen = 0;
    uint32_t framesChecked = 0;
    double fencedMs = 0, stampedMs = 0;  // the check's frames, fenced and as their timestamps saw them
    bool checking = false;  // the renderer fences the frames of a check
    bool fenced = false;    // the budget reads fenced frames (the renderer times every frame so)
    double coverage = -1;
  } timing_;
  ChangeTracker changes_;  // the one change set per frame
  ChangeSet pending_;      // changes not yet handed to the technique (run() more often than render())
  double syncMs_ = 0;      // run() plus the last updateTechnique()
};

}  // namespace dyngi::gi
