// Voxel cone tracing in the GI system's contract (`--gi vct`): radiance injected into the voxel scene
// every frame, filtered into a 3D mip chain, traced by cones from the screen.
#include <algorithm>
#include <cmath>
#include <vector>

#include "dyngi/engine/ecs/entity_map.h"
#include "dyngi/gi/gi_settings.h"
#include "gpu_aliases.h"
#include "indirect/emitters.h"
#include "techniques/vct/shaders/vct_shared.h"
#include "techniques/vct/voxel_cone_tracing.h"
#include "techniques/registry_entries.h"

namespace dyngi::gi {

const OptionTable<VctOptions>& VctOptions::table() {
  static const OptionTable<VctOptions> t =
      OptionTable<VctOptions>()
          .add(DYNGI_OPTION(VctOptions, diffuseCones), "diffuse cones per pixel (cosine-spread over the hemisphere)", 1, 32)
          .add(DYNGI_OPTION(VctOptions, coneInterleave), "rows of traced pixels take turns over the diffuse cones, each marching every Nth (with --diffuse-filter-radius 0: 1)", 1, 4)
          .add(DYNGI_OPTION(VctOptions, bounces), "light bounces (each past the first: a cone pass over the occupied voxels)", 1, 3)
          .add(DYNGI_OPTION(VctOptions, bounceFrames), "frames over which every occupied voxel updates the bounce light it carries, which adds a bounce each turn (0: off)", 0, 64)
          .add(DYNGI_OPTION(VctOptions, emitterSamples), "points on the emissive surfaces whose shadowed light each voxel takes, without --bounce-frames (0: off; 1, 2 or 4)", 0, DYNGI_VCT_EMITTER_MAX_SAMPLES)
          .add(DYNGI_OPTION(VctOptions, emitterFrames), "frames over which every voxel's emitter light is updated once", 1, 64)
          .add(DYNGI_OPTION(VctOptions, traceScale), "trace one pixel in NxN and upsample (1: every pixel; 0: at most 192^2 traced)", 0, 8)
          .add(DYNGI_OPTION(VctOptions, traceFrames), "frames over which each traced pixel is traced once, the rest reprojected (1, 2 or 4)", 1, 4)
          .add(DYNGI_OPTION(VctOptions, radianceFrames), "frames over which the voxels' radiance update is spread, a part of the voxels each", 1, 4)
          .add(DYNGI_OPTION(VctOptions, diffuseFilterRadius), "radius (traced pixels) of the filter over cone sets turned per pixel (0: fixed cones, no filter)", 0, VctOptions::kMaxDiffuseFilterRadius)
          .add(DYNGI_OPTION(VctOptions, anisotropic), "mip chain per direction (less light leaks through thin walls)", 0, 1)
          .add(DYNGI_OPTION(VctOptions, opaqueAxisMips), "isotropic mips take their most opaque axis' opacity, not the mean (thin walls stay opaque)", 0, 1)
          .add(DYNGI_OPTION(VctOptions, specular), "specular cone from the G-buffer roughness", 0, 1)
          .add(DYNGI_OPTION(VctOptions, specularConeBelow), "roughness under which the specular light is a cone's; rougher pixels take the diffuse light (E/pi), blended over the 0.2 under it (over 1: always a cone)", 0.2, 2)
          .add(DYNGI_OPTION(VctOptions, temporalBlend), "fraction of last frame's voxel radiance kept (0: none)", 0, 0.95)
          .add(DYNGI_OPTION(VctOptions, temporalResponse), "relative change above which a voxel takes the new radiance at once", 0.01, 10)
          .add(DYNGI_OPTION(VctOptions, maxDistance), "cone reach, in volume sides", 0.05, 2)
          .add(DYNGI_OPTION(VctOptions, aoDistance), "reach of ambient occlusion, in volume sides", 0.01, 1)
          .add(DYNGI_OPTION(VctOptions, coneOffset), "voxels off the surface a cone starts", 0, 4)
          .add(DYNGI_OPTION(VctOptions, coneStep), "step along a cone, in cone diameters", 0.1, 2)
          .add(DYNGI_OPTION(VctOptions, farNarrowing), "samples of footprints over 11 voxels read a footprint 2^-B of the cone's (less light through thin walls; with few --diffuse-cones, light between them is lost)", 0, 1)
          .add(DYNGI_OPTION(VctOptions, viewMip), "mip level the radiance and opacity views show", 0, 9);
  return t;
}

namespace {

class VctTechnique final : public Technique {
 public:
  VctTechnique(const TechniqueServices& services, const VctOptions& options)
      : assets_(services.assets), voxels_(*services.voxels), feature_(services.ctx, *services.voxels, options) {}
  std::vector<render::RenderFeature*> features() override { return {&feature_}; }
  // The traced pixels kept from earlier frames (trace-frames > 1) lag a change by up to that many frames:
  // fine for things that move a little each frame, not for light that appears, goes or jumps at once.
  // Dropped when a light is switched on or off or its radiance changes by more than the voxels' temporal
  // response, a material is written (an emission switched), or a light or a mesh jumps (more than
  // kJumpFraction of the voxel volume's side, or a light turns more than kJumpRadians, in one frame).
  void update(const TechniqueFrame& frame) override {
    const VoxelVolume& volume = voxels_.volume();
    const float jump = kJumpFraction * volume.voxelSize * float(volume.resolution);
    bool drop = !frame.changes.materials.empty() || frame.snapshot.lights.size() != lights_.size();
    std::vector<LightState> lights;
    const float response = feature_.settings().temporalResponse;
    for (size_t i = 0; i < frame.snapshot.lights.size(); ++i) {
      const render::LightItem& l = frame.snapshot.lights[i];
      lights.push_back({l.entity, l.light.enabled ? l.light.color * l.light.intensity : glm::vec3(0.0f), l.position, l.direction});
      if (drop) continue;
      const LightState &before = lights_[i], &now = lights.back();
      drop = now.entity != before.entity ||
             glm::length(now.radiance - before.radiance) > response * std::max(glm::length(before.radiance), glm::length(now.radiance)) ||
             glm::distance(now.position, before.position) > jump ||
             glm::dot(now.direction, before.direction) < std::cos(kJumpRadians);
    }
    // Meshes: only those the change set says moved or were written can have jumped; the others keep
    // their place from the frame they last changed.
    if (!frame.changes.moved.empty() || !frame.changes.meshWritten.empty()) {
      ecs::EntitySet touched;
      touched.insert(frame.changes.moved.begin(), frame.changes.moved.end());
      touched.insert(frame.changes.meshWritten.begin(), frame.changes.meshWritten.end());
      for (const render::DrawItem& d : frame.snapshot.draws) {
        if (!touched.count(d.entity)) continue;
        const glm::vec3 at(d.model[3]);
        if (auto it = places_.find(d.entity); it != places_.end()) {
          drop = drop || glm::distance(at, it->second) > jump;
          it->second = at;
        } else {
          places_.emplace(d.entity, at);
        }
      }
    }
    for (scene::Entity e : frame.changes.removed) places_.erase(e);
    if (drop) {
      feature_.dropTraceHistory();
      feature_.refreshCarriedLight();
      ++historyDrops_;
    }
    lights_ = std::move(lights);
    sampleEmitters(frame);
  }
  // A frame that traced every pixel although the trace is spread (the first, or after a drop) costs
  // traceFrames times the trace: a GI budget leaves it out. Under a budget there is none: such a frame
  // traces its share too (spreadOneOffWork).
  bool lastFrameWasOneOff() const override {
    const VctFrameStats& s = feature_.stats();
    return (s.tracedFraction == 1.0 && feature_.settings().traceFrames > 1) || (s.carriedUpdated == 1.0 && feature_.carriedFrames() > 1);
  }
  void spreadOneOffWork(bool spread) override { feature_.setSpreadTraceWithoutHistory(spread); }
  std::vector<OptionRef> options() override { return bindOptions(feature_.settings()); }
  bool setDebugView(std::string_view name) override {
    VctView& v = feature_.settings().view;
    if (name == "final") v = VctView::Final;
    else if (name == "radiance") v = VctView::Radiance;
    else if (name == "opacity") v = VctView::Opacity;
    else if (name == "ao") v = VctView::Ao;
    else if (name == "specular") v = VctView::Specular;
    else return false;
    return true;
  }
  std::vector<const char*> timedSections() const override { return VoxelConeTracing::timedSections(); }
  // First the fraction of its pixels the trace keeps (1, 1/4, 1/16: the trace scale times 1, 2, 4): the
  // cone trace scales with it; the upsample fills the rest. Then the share of the voxels whose radiance
  // a frame updates (1, 1/2, 1/3, 1/4: injection and mips spread over 2 to 4 frames), which costs nothing
  // while the light holds still and makes a change take that many frames to reach every voxel. Not the
  // voxel updates' fraction of frames (VoxelScene::updateFractionKnob): with geometry moving, updating
  // the voxels one frame in N makes the frames' cost bimodal (docs/QUALITY.md, "The GI budget").
  // With the carried bounce light on, its update rate comes first (1, 1/2, 1/4 of the voxels'
  // --bounce-frames rate; under 1 a moved object's new voxels wait for their turn too): in a still scene
  // it loses nothing, only the carried light's response to a change slows by as much.
  std::vector<QualityKnob> qualityKnobs() override {
    std::vector<QualityKnob> knobs;
    if (feature_.settings().bounceFrames > 0)
      knobs.push_back({"carried_update_fraction", {1.0, 0.5, 0.25},
                       [this](double v) { feature_.setBudgetCarriedSlowdown(uint32_t(std::lround(1.0 / std::max(v, 1e-6)))); }});
    knobs.push_back({"trace_fraction", {1.0, 0.25, 0.0625},
                     [this](double v) { feature_.setBudgetScaleFactor(uint32_t(std::lround(1.0 / std::sqrt(std::max(v, 1e-6))))); }});
    knobs.push_back({"radiance_update_fraction", {1.0, 1.0 / 2, 1.0 / 3, 1.0 / 4},
                     [this](double v) { feature_.setBudgetRadianceParts(uint32_t(std::lround(1.0 / std::max(v, 1e-6)))); }});
    return knobs;
  }
  std::map<std::string, std::map<std::string, double>> statsSections() const override {
    const VctFrameStats& s = feature_.stats();
    return {{"vct",
             {{"trace_width", s.traceWidth}, {"trace_height", s.traceHeight}, {"volume_mib", double(s.volumeBytes) / (1 << 20)},
              {"trace_scale", feature_.traceScale()},
              {"trace_fraction", 1.0 / double(feature_.budgetScaleFactor() * feature_.budgetScaleFactor())},
              {"traced_this_frame", s.tracedFraction},
              {"specular_cones", s.specularCones ? 1.0 : 0.0},
              {"trace_history_drops", double(historyDrops_)},
              {"cleared_voxels", double(s.clearedVoxels)},
              {"voxel_update_fraction", 1.0 / double(voxels_.updateInterval())},
              {"radiance_update_fraction", 1.0 / double(feature_.radianceParts())},
              {"radiance_updated_this_frame", s.radianceUpdated},
              {"carried_update_fraction", 1.0 / double(feature_.budgetCarriedSlowdown())},
              {"carried_updated_this_frame", s.carriedUpdated},
              {"emitter_light", feature_.carriesEmitterLight() ? 1.0 : 0.0}}}};
  }

 private:
  static constexpr float kJumpFraction = 0.05f, kJumpRadians = 0.1f;
  // The points on the emitters the voxels' emitter light is estimated from (VctOptions::emitterSamples):
  // the same stratified draw each time, so a still scene gives the same points and the voxels no flicker;
  // drawn again only when a mesh or a material changed (or the options turned it on or off).
  void sampleEmitters(const TechniqueFrame& frame) {
    const ChangeSet& c = frame.changes;
    const bool want = feature_.settings().emitterSamples > 0 && feature_.settings().bounceFrames == 0;
    if (want == sampledEmitters_ && c.moved.empty() && c.deformed.empty() && c.meshWritten.empty() && c.removed.empty() && c.materials.empty())
      return;
    sampledEmitters_ = want;
    std::vector<gpu::VctEmitterPoint> points;
    if (want) {
      const EmitterSet emitters(frame.snapshot, assets_);
      if (!emitters.empty()) {
        points.resize(DYNGI_VCT_EMITTER_POINTS);
        for (uint32_t k = 0; k < DYNGI_VCT_EMITTER_POINTS; ++k) {
          // Stratified over the power; the point in the triangle from the R2 sequence.
          const float u1 = std::fmod(0.5f + 0.7548776662f * float(k), 1.0f), u2 = std::fmod(0.5f + 0.5698402910f * float(k), 1.0f);
          const EmitterSample e = emitters.sample((float(k) + 0.5f) / float(DYNGI_VCT_EMITTER_POINTS), u1, u2, 0.0f);
          points[k] = {glm::vec4(e.position, e.pdfArea), glm::vec4(e.faceNormal, 0.0f), glm::vec4(e.radiance, 0.0f)};
        }
      }
    }
    feature_.setEmitterPoints(points);
  }
  const scene::AssetStore& assets_;
  bool sampledEmitters_ = false;  // the points were drawn for the options as they stand
  struct LightState {
    scene::Entity entity;
    glm::vec3 radiance;  // colour x intensity, 0 when disabled
    glm::vec3 position, direction;
  };
  VoxelScene& voxels_;
  VoxelConeTracing feature_;
  std::vector<LightState> lights_;                          // as last frame saw them
  ecs::EntityMap<glm::vec3> places_;     // each mesh's origin when it last changed
  uint64_t historyDrops_ = 0;
};

}  // namespace

TechniqueEntry vctTechniqueEntry() {
  return {"vct",
          "voxel cone tracing: direct light injected into the voxel volume, a 3D mip chain, diffuse, AO and specular cones",
          {"radiance", "opacity", "ao", "specular"},
          [](GiSettings& s) { return bindOptions(s.vct); },
          [](const GiSettings&) { return true; },
          [](const GiSettings&) { return false; },
          [](const TechniqueServices& services, const GiSettings& s) -> std::unique_ptr<Technique> {
            return std::make_unique<VctTechnique>(services, s.vct);
          }};
}

}  // namespace dyngi::gi
