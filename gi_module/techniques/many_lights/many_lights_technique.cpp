// The many-lights technique in the GI system's contract: VPLs from RSMs every frame, SVO visibility.
#include "dyngi/gi/gi_settings.h"
#include "techniques/many_lights/many_lights.h"
#include "indirect/indirect_passes.h"
#include "indirect/reduced_screen.h"
#include "techniques/registry_entries.h"

namespace dyngi::gi {

const OptionTable<ManyLightsOptions>& ManyLightsOptions::table() {
  static const OptionTable<ManyLightsOptions> t =
      OptionTable<ManyLightsOptions>()
          .include(&ManyLightsOptions::vpl)
          .add(DYNGI_OPTION(ManyLightsOptions, rsmResolution), "reflective shadow map texels per side and light", 16, 2048, /*powerOfTwo=*/true)
          .addChoice(DYNGI_OPTION(ManyLightsOptions, visibility), "whether a VPL sees a pixel: marched through the SVO, or none (V = 1, for comparisons)",
                     {{"svo", VisibilityBackend::Svo}, {"none", VisibilityBackend::None}});
  return t;
}

namespace {

class ManyLightsTechnique final : public Technique {
 public:
  ManyLightsTechnique(const TechniqueServices& services, const ManyLightsOptions& options)
      : assets_(services.assets), voxels_(*services.voxels), feature_(services.ctx, *services.voxels, options) {}
  std::vector<render::RenderFeature*> features() override { return {&feature_}; }
  void update(const TechniqueFrame& frame) override { feature_.prepareEmitters(frame.snapshot, assets_); }
  std::vector<OptionRef> options() override { return bindOptions(feature_.settings()); }
  bool setDebugView(std::string_view name) override {
    ManyLightsView& v = feature_.settings().view;
    if (name == "final") v = ManyLightsView::Final;
    else if (name == "vpls") v = ManyLightsView::Vpls;
    else if (name == "subimages") v = ManyLightsView::SubImages;
    else return false;
    return true;
  }
  std::vector<const char*> timedSections() const override {
    std::vector<const char*> s = {"rsm", "vpl_generate", "vpl_bounce", "indirect", "filter"};
    if (IndirectFilterPass::compensates(feature_.settings().vpl)) s.push_back("compensate");
    if (feature_.screenReduced()) s.insert(s.end(), {"reduce", "upsample"});
    return s;
  }
  // First the fraction of pixels the gather and the filter run on (ReducedScreen): per millisecond
  // saved it loses the least (docs/QUALITY.md, "The GI budget"). Then the VPLs per frame: cost
  // proportional to them in every stage after the RSMs. Then the bounce tail's probes gathered
  // (tailStrideKnob): they lower the floor the tail raises. Last the fraction of frames that update the
  // voxels (their cost is lag).
  std::vector<QualityKnob> qualityKnobs() override {
    const uint32_t bounces = feature_.settings().vpl.bounces;
    std::vector<QualityKnob> knobs = {gatherFractionKnob([this](float factor) { feature_.setBudgetGatherScale(factor); }),
                                      {"vpls_per_frame", geometricLevels(feature_.vplCount(), kBudgetFloorFraction, kBudgetStepRatio, bounces),
                                       [this](double v) { feature_.setVplsPerFrame(uint32_t(v)); }}};
    for (QualityKnob& k : tailStrideKnob(feature_.settings().vpl, [this](uint32_t s) { feature_.setTailStride(s); })) knobs.push_back(std::move(k));
    knobs.push_back(voxels_.updateFractionKnob());
    return knobs;
  }
  std::map<std::string, std::map<std::string, double>> statsSections() const override {
    return {{"vpl", {{"count", feature_.vplCount()}, {"gather_scale", feature_.gatherScale()},
                     {"gather_fraction", 1.0 / (double(feature_.budgetGatherScale()) * feature_.budgetGatherScale())},
                     {"tail_stride", feature_.tailStride()},
                     {"voxel_update_fraction", 1.0 / double(voxels_.updateInterval())}}}};
  }
  ManyLights& feature() { return feature_; }

 private:
  const scene::AssetStore& assets_;
  VoxelScene& voxels_;
  ManyLights feature_;
};

}  // namespace

TechniqueEntry manyLightsTechniqueEntry() {
  return {"many-lights",
          "VPLs importance-sampled from reflective shadow maps every frame, bounced and gathered with SVO visibility",
          {"vpls", "subimages"},
          [](GiSettings& s) { return bindOptions(s.manyLights); },
          [](const GiSettings&) { return true; },
          [](const GiSettings&) { return false; },
          [](const TechniqueServices& services, const GiSettings& s) -> std::unique_ptr<Technique> {
            return std::make_unique<ManyLightsTechnique>(services, s.manyLights);
          }};
}

}  // namespace dyngi::gi
