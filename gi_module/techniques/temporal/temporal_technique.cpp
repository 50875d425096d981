// The temporal technique in the GI system's contract: incremental VPL paths on the CPU (VplPaths),
// temporal sets gathered one a frame and reprojected (TemporalIndirect), SVO or Embree visibility.
#include "dyngi/gi/gi_settings.h"
#include "techniques/temporal/temporal_indirect.h"
#include "techniques/temporal/vpl_paths.h"
#include "techniques/temporal/shaders/temporal_shared.h"
#include "indirect/indirect_passes.h"
#include "indirect/reduced_screen.h"
#include "techniques/registry_entries.h"

namespace dyngi::gi {

const OptionTable<TemporalOptions>& TemporalOptions::table() {
  static const OptionTable<TemporalOptions> t =
      OptionTable<TemporalOptions>()
          .include(&TemporalOptions::vpl)
          .addChoice(DYNGI_OPTION(TemporalOptions, visibility), "whether a VPL sees a pixel: SVO march on the GPU, Embree rays on the CPU (exact), or none (V = 1)",
                     {{"svo", VisibilityBackend::Svo}, {"bvh", VisibilityBackend::Bvh}, {"none", VisibilityBackend::None}})
          .add(DYNGI_OPTION(TemporalOptions, temporalSets), "T temporal VPL sets, one gathered a frame (1: every VPL every frame)", 1, DYNGI_MAX_TEMPORAL_SETS)
          .add(DYNGI_OPTION(TemporalOptions, reshootBudget), "VPLs reshot per frame (0: VPLs / T)", 0, 1000000)
          .add(DYNGI_OPTION(TemporalOptions, reshootBurst), "all invalid VPLs up to this many are reshot at once when more than the budget are (0: off)", 0, 1000000)
          .add(DYNGI_OPTION(TemporalOptions, dropStaleSets), "a set more than this fraction stale leaves the average until regathered (1: never)", 0, 1)
          .add(DYNGI_OPTION(TemporalOptions, catchUpSets), "sets gathered in one frame while some hold no light (start, after a light change)", 1, DYNGI_MAX_TEMPORAL_SETS)
          .add(DYNGI_OPTION(TemporalOptions, reprojectionCutoff), "a stored sample counts within this fraction of the view distance", 0, 1)
          .add(DYNGI_OPTION(TemporalOptions, lightMoveTolerance), "a light's VPLs live until it moved this fraction of the scene diagonal", 0, 1)
          .add(DYNGI_OPTION(TemporalOptions, lightTurnTolerance), "... or turned this many radians", 0, 3.2)
          .add(DYNGI_OPTION(TemporalOptions, incrementalAccumulation), "O(1) accumulation while the camera is still (off: full reprojection every frame)", 0, 1);
  return t;
}

namespace {

class TemporalTechnique final : public Technique {
 public:
  TemporalTechnique(const TechniqueServices& services, const TemporalOptions& options)
      : bvh_(*services.bvh), assets_(services.assets), voxels_(services.voxels), paths_(options),
        feature_(services.ctx, paths_, services.voxels, services.bvh) {}

  // VPLs on a re-coloured surface keep their paths and take the new albedo (so does every later bounce);
  // those on a surface that moved or deformed, with their later bounces, are invalidated; then up to the
  // budget are reshot.
  void update(const TechniqueFrame& frame) override {
    const ecs::EntitySet geometry = frame.changes.geometryChanged();
    ecs::EntitySet recoloured;
    for (ecs::Entity e : frame.changes.materials)
      if (!geometry.count(e)) recoloured.insert(e);
    paths_.refreshMaterials(frame.snapshot, bvh_, assets_, recoloured);
    paths_.update(frame.snapshot, bvh_, assets_, geometry);
  }
  std::vector<render::RenderFeature*> features() override { return {&feature_}; }
  std::vector<OptionRef> options() override {
    used_ = paths_.settings();
    used_.vpl.interleave = feature_.settings().vpl.interleave;
    return bindOptions(used_);
  }
  std::vector<const char*> timedSections() const override {
    std::vector<const char*> s = {"indirect", "reproject", "filter"};
    if (IndirectFilterPass::compensates(feature_.settings().vpl)) s.push_back("compensate");
    if (feature_.screenReduced()) s.insert(s.end(), {"reduce", "upsample"});
    return s;
  }
  std::map<std::string, double> cpuMs() const override {
    const VplPathStats& s = paths_.stats();
    std::map<std::string, double> ms = {{"gi_vpl_invalidate", s.invalidateMs}, {"gi_vpl_replace", s.replaceMs}};
    if (paths_.settings().visibility == VisibilityBackend::Bvh) ms["gi_bvh_visibility"] = feature_.lastBvhVisibilityMs();
    return ms;
  }
  std::map<std::string, std::map<std::string, double>> statsSections() const override {
    const VplPathStats& s = paths_.stats();
    return {{"vpl",
             {{"count", s.count},
              {"valid", s.valid},
              {"invalidated_total", double(s.invalidatedTotal)},
              {"replaced_total", double(s.replacedTotal)},
              {"reshoot_budget", s.reshootBudget},
              {"vpls_per_frame", feature_.vplsPerFrame()},
              {"gather_scale", feature_.gatherScale()},
              {"gather_fraction", 1.0 / (double(feature_.budgetGatherScale()) * feature_.budgetGatherScale())},
              {"tail_stride", feature_.tailStride()},
              {"voxel_update_fraction", voxels_ ? 1.0 / double(voxels_->updateInterval()) : 1.0},
              {"trapped_last_frame", feature_.lastTrappedVpls()}}}};
  }
  // First the fraction of pixels the gather, the reprojection and the filter run on (ReducedScreen):
  // per millisecond saved it loses the least (docs/QUALITY.md, "The GI budget"). Then the VPLs gathered
  // per frame (an evenly spread subset of the set): the gather's cost is proportional to them. Then the
  // bounce tail's probes gathered (tailStrideKnob): they lower the floor the tail raises. Last,
  // with SVO visibility, the fraction of frames that update the voxels (their cost is lag). Not the interleave K: K = 8 saves 37 ms of gather and adds 22 ms of filter at 768^2 (the
  // filter's window is K x K). Not the reshoot budget: its cost is CPU path tracing (0.02 ms here) and
  // lowering it is exactly what slows the reaction to a change.
  // Its floor gathers at least one VPL in each of the K x K sub-images: one with none would have no
  // estimate to scale (and gathering fewer costs no less: every pixel walks at least one VPL).
  std::vector<QualityKnob> qualityKnobs() override {
    const double set = feature_.setSize(), K = std::clamp(feature_.settings().vpl.interleave, 1u, 8u);
    const double floorFraction = std::min(1.0, std::max(kBudgetFloorFraction, K * K / set));
    std::vector<QualityKnob> knobs = {gatherFractionKnob([this](float factor) { feature_.setBudgetGatherScale(factor); }),
                                      {"vpls_per_frame", geometricLevels(set, floorFraction, kBudgetStepRatio),
                                       [this](double v) { feature_.setVplsPerFrame(uint32_t(v)); }}};
    for (QualityKnob& k : tailStrideKnob(feature_.settings().vpl, [this](uint32_t s) { feature_.setTailStride(s); })) knobs.push_back(std::move(k));
    if (voxels_) knobs.push_back(voxels_->updateFractionKnob());  // SVO visibility
    return knobs;
  }
  bool lastFrameWasOneOff() const override { return feature_.lastFrameSetCount() > 1; }
  void spreadOneOffWork(bool spread) override { feature_.setCatchUpOneSetAFrame(spread); }
  VplPaths& paths() { return paths_; }
  TemporalIndirect& feature() { return feature_; }

 private:
  EmbreeScene& bvh_;
  const scene::AssetStore& assets_;
  VoxelScene* voxels_;  // with SVO visibility
  VplPaths paths_;
  TemporalIndirect feature_;
  TemporalOptions used_;  // what options() binds: the paths' options as used
};

}  // namespace

TechniqueEntry temporalTechniqueEntry() {
  return {"temporal",
          "incremental VPL light paths, T temporal sets gathered one a frame and reprojected; SVO or Embree visibility",
          {},
          [](GiSettings& s) { return bindOptions(s.temporal); },
          [](const GiSettings& s) { return s.temporal.visibility == VisibilityBackend::Svo; },
          [](const GiSettings&) { return true; },  // the VPL paths' rays, and the visibility with --visibility bvh
          [](const TechniqueServices& services, const GiSettings& s) -> std::unique_ptr<Technique> {
            return std::make_unique<TemporalTechnique>(services, s.temporal);
          }};
}

}  // namespace dyngi::gi
