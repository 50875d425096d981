// Voxel cone tracing in the GI system's contract (`--gi vct`): radiance injected into the voxel scene
// every frame, filtered into a 3D mip chain, traced by cones from the screen.
#include <cmath>

#include "dyngi/gi/gi_settings.h"
#include "dyngi/gi/voxel_cone_tracing.h"
#include "techniques/registry_entries.h"

namespace dyngi::gi {

const OptionTable<VctOptions>& VctOptions::table() {
  static const OptionTable<VctOptions> t =
      OptionTable<VctOptions>()
          .add({"cones", "diffuse cones per pixel (cosine-spread over the hemisphere)", 1, 32}, &VctOptions::diffuseCones)
          .add({"bounces", "light bounces (each past the first: a cone pass over the occupied voxels)", 1, 3}, &VctOptions::bounces)
          .add({"trace-scale", "trace one pixel in NxN and upsample (1: every pixel)", 1, 4}, &VctOptions::traceScale)
          .add({"anisotropic", "mip chain per direction (less light leaks through thin walls)", 0, 1}, &VctOptions::anisotropic)
          .add({"specular", "specular cone from the G-buffer roughness", 0, 1}, &VctOptions::specular)
          .add({"temporal-blend", "fraction of last frame's voxel radiance kept (0: none)", 0, 0.95}, &VctOptions::temporalBlend)
          .add({"temporal-response", "relative change above which a voxel takes the new radiance at once", 0.01, 10},
               &VctOptions::temporalResponse)
          .add({"max-distance", "cone reach, in volume sides", 0.05, 2}, &VctOptions::maxDistance)
          .add({"ao-distance", "reach of ambient occlusion, in volume sides", 0.01, 1}, &VctOptions::aoDistance)
          .add({"cone-offset", "voxels off the surface a cone starts", 0, 4}, &VctOptions::coneOffset)
          .add({"cone-step", "step along a cone, in cone diameters", 0.1, 1}, &VctOptions::stepScale)
          .add({"view-mip", "mip level the radiance and opacity views show", 0, 9}, &VctOptions::viewMip);
  return t;
}

namespace {

constexpr uint32_t kMaxBudgetTraceScale = 4;  // a GI budget traces at least one pixel in 4 x 4

class VctTechnique final : public Technique {
 public:
  VctTechnique(const TechniqueServices& services, const VctOptions& options) : feature_(services.ctx, *services.voxels, options) {}
  std::vector<render::RenderFeature*> features() override { return {&feature_}; }
  std::vector<OptionRef> options() override { return bindOptions(feature_.settings()); }
  bool setDebugView(std::string_view name) override {
    VctView& v = feature_.settings().view;
    if (name == "final") v = VctView::Final;
    else if (name == "radiance") v = VctView::Radiance;
    else if (name == "opacity") v = VctView::Opacity;
    else if (name == "ao") v = VctView::Ao;
    else if (name == "indirect") v = VctView::Indirect;
    else if (name == "specular") v = VctView::Specular;
    else return false;
    return true;
  }
  std::vector<const char*> timedSections() const override { return VoxelConeTracing::timedSections(); }
  // The fraction of pixels traced (1 / traceScale^2): the cone trace is most of the cost and scales with
  // it; the upsample fills the rest. From the options' scale to one pixel in 4 x 4.
  std::vector<QualityKnob> qualityKnobs() override {
    std::vector<double> levels;
    for (uint32_t s = std::max(feature_.settings().traceScale, 1u); s <= kMaxBudgetTraceScale; s *= 2) levels.push_back(1.0 / double(s * s));
    return {{"traced_fraction", levels,
             [this](double v) { feature_.setTraceScale(uint32_t(std::lround(1.0 / std::sqrt(std::max(v, 1e-6))))); }}};
  }
  std::map<std::string, std::map<std::string, double>> statsSections() const override {
    const VctFrameStats& s = feature_.stats();
    return {{"vct",
             {{"trace_width", s.traceWidth}, {"trace_height", s.traceHeight}, {"volume_mib", double(s.volumeBytes) / (1 << 20)},
              {"trace_scale", feature_.traceScale()}, {"traced_fraction", 1.0 / double(feature_.traceScale() * feature_.traceScale())}}}};
  }

 private:
  VoxelConeTracing feature_;
};

}  // namespace

TechniqueEntry vctTechniqueEntry() {
  return {"vct",
          "voxel cone tracing: direct light injected into the voxel volume, a 3D mip chain, diffuse, AO and specular cones",
          {"radiance", "opacity", "ao", "indirect", "specular"},
          [](GiSettings& s) { return bindOptions(s.vct); },
          [](const GiSettings&) { return true; },
          [](const TechniqueServices& services, const GiSettings& s) -> std::unique_ptr<Technique> {
            return std::make_unique<VctTechnique>(services, s.vct);
          }};
}

}  // namespace dyngi::gi
