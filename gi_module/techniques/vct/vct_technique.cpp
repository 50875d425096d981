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
          .add({"trace-scale", "trace one pixel in NxN and upsample (1: every pixel; 0: at most 192^2 traced)", 0, 8},
               &VctOptions::traceScale)
          .add({"diffuse-filter", "radius (traced pixels) of the filter over cone sets turned per pixel (0: fixed cones, no filter)", 0,
                VctOptions::kMaxDiffuseFilterRadius},
               &VctOptions::diffuseFilterRadius)
          .add({"anisotropic", "mip chain per direction (less light leaks through thin walls)", 0, 1}, &VctOptions::anisotropic)
          .add({"opaque-axis-mips", "isotropic mips take their most opaque axis' opacity, not the mean (thin walls stay opaque)", 0, 1},
               &VctOptions::opaqueAxisMips)
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
  // The fraction of its pixels the trace keeps (1, 1/4, 1/16: the trace scale times 1, 2, 4): the cone
  // trace is most of the cost and scales with it; the upsample fills the rest.
  std::vector<QualityKnob> qualityKnobs() override {
    return {{"trace_fraction", {1.0, 0.25, 0.0625},
             [this](double v) { feature_.setBudgetScaleFactor(uint32_t(std::lround(1.0 / std::sqrt(std::max(v, 1e-6))))); }}};
  }
  std::map<std::string, std::map<std::string, double>> statsSections() const override {
    const VctFrameStats& s = feature_.stats();
    return {{"vct",
             {{"trace_width", s.traceWidth}, {"trace_height", s.traceHeight}, {"volume_mib", double(s.volumeBytes) / (1 << 20)},
              {"trace_scale", feature_.traceScale()},
              {"trace_fraction", 1.0 / double(feature_.budgetScaleFactor() * feature_.budgetScaleFactor())}}}};
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
