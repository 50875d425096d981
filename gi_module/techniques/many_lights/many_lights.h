#pragma once
// Many-lights GI with SVO visibility (after Sun & Agu): reflective shadow maps per light, VPLs
// importance-sampled from RSM flux, extra bounces shot through the voxel scene, an interleaved KxK
// gather with SVO-restart visibility, a geometry-aware merge filter. Writes targets.indirect; the
// engine's lighting pass adds albedo x indirect to direct light. Stages: rsm, vpl_generate, vpl_bounce,
// indirect, filter (plus the voxel scene's voxelize and svo_build; reduce and upsample when the gather
// runs on a smaller screen, ReducedScreen).
#include <algorithm>
#include <memory>
#include <vector>

#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/gi/many_lights_options.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

struct VplReadback;  // gi_module/testing/gi_probes.h

class ManyLights final : public render::RenderFeature {
 public:
  ManyLights(render::VulkanContext& ctx, VoxelScene& voxels, const ManyLightsOptions& settings = {});
  ~ManyLights() override;

  const char* name() const override { return "many_lights"; }
  void prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) override;
  bool record(render::FrameContext& frame) override;
  void recordAfterLighting(render::FrameContext& frame) override;
  void resize(render::VulkanContext& ctx, uint32_t width, uint32_t height) override;

  ManyLightsOptions& settings() { return settings_; }
  const ManyLightsOptions& settings() const { return settings_; }
  // VPLs per frame as used: the requested count rounded down to a multiple of the bounces, or fewer
  // while a GI budget lowers it (setVplsPerFrame; 0 gives the requested count back).
  uint32_t vplCount() const {
    const uint32_t requested = settings_.vpl.effectiveVplCount(), b = std::clamp(settings_.vpl.bounces, 1u, 3u);
    return perFrame_ ? std::clamp(perFrame_ / b * b, b, requested) : requested;
  }
  void setVplsPerFrame(uint32_t count) { perFrame_ = count; }
  // How many times smaller a side the gather's and filter's screen is (ReducedScreen):
  // VplOptions::gatherScale times a GI budget's factor (setBudgetGatherScale).
  float gatherScale() const { return std::clamp(settings_.vpl.gatherScale * budgetGatherScale_, 1.0f, 8.0f); }
  void setBudgetGatherScale(float factor) { budgetGatherScale_ = std::max(1.0f, factor); }
  float budgetGatherScale() const { return budgetGatherScale_; }
  // The bounce tail gathers one probe in this many (VplOptions::bounceTailStride until a GI budget moves it).
  uint32_t tailStride() const { return tailStride_; }
  void setTailStride(uint32_t stride) { tailStride_ = std::max(1u, stride); }
  // Whether the screen passes run on a smaller screen (then "reduce" and "upsample" are timed).
  bool screenReduced() const;
  // Emissive surfaces as VPL sources (vpl/emitters.h), before prepare(): the first bounce's VPLs are
  // split between the RSMs and the emitters in proportion to the lights' and the emitters' power; the
  // emitters' are sampled here on the CPU (stratified, the same every frame while nothing changes).
  // Without a call (the feature used on its own) only the lights make VPLs.
  void prepareEmitters(const render::RenderSnapshot& snapshot, const scene::AssetStore& assets);
  uint32_t emitterVplCount() const { return uint32_t(emitterVpls_.size()); }

 private:
  friend std::vector<VplReadback> readbackVpls(ManyLights&, bool);  // tests (gi_module/testing)
  void ensureRsm(uint32_t layers);
  void recordReflectiveShadowMaps(render::FrameContext& frame);
  void recordVplGeneration(render::FrameContext& frame);
  void recordVplBounces(render::FrameContext& frame);
  void recordGatherAndFilter(render::FrameContext& frame);
  // The VPLs a frame gathers: every simulated bounce's, and with the bounce tail its probes (one per run
  // of tailStride last-bounce VPLs).
  uint32_t tailProbeCount() const { return settings_.vpl.bounceTail ? (perBounce_ + tailStride_ - 1) / tailStride_ : 0u; }
  uint32_t gatheredVplCount() const { return perBounce_ * settings_.vpl.bounces + tailProbeCount(); }

  render::VulkanContext& ctx_;
  VoxelScene& voxels_;
  ManyLightsOptions settings_;
  uint32_t rsmLayers_ = 0, rsmLayersUsed_ = 0, perBounce_ = 0;
  uint32_t perFrame_ = 0;  // a GI budget's VPL count (0: the options')
  float budgetGatherScale_ = 1.0f;
  uint32_t tailStride_ = 1;
  uint32_t width_ = 0, height_ = 0;  // the frame's (resize)
  render::Image rsmPosition_, rsmNormal_, rsmFlux_, rsmDepth_;
  render::Buffer layers_, lights_, rowPrefix_, rowCdf_, vpls_;
  struct EmitterVpl {  // gpu::GpuVpl's layout
    glm::vec4 position, normal, flux;
  };
  std::vector<EmitterVpl> emitterVpls_;  // this frame's VPLs on emissive surfaces (prepareEmitters)
  render::Buffer emitterUpload_;
  render::Image raw_;
  // One RSM pipeline per material kind (which textures it binds), made on first use: lavapipe would
  // run the lookup of a branch not taken.
  render::Pipeline rsm_[16];  // by the base-colour, metallic-roughness and normal texture bits and the alpha mask
  render::Pipeline& rsmPipelineFor(uint32_t textureBits);
  render::Pipeline cdfRows_, cdfTotal_, sample_, bounce_, tail_, debug_;
  std::unique_ptr<class IndirectGatherPass> gatherPass_;
  std::unique_ptr<class IndirectFilterPass> filterPass_;
  std::unique_ptr<class ReducedScreen> reduced_;
};

}  // namespace dyngi::gi
