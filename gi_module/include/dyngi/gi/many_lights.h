#pragma once
// Many-lights GI with SVO visibility (after Sun & Agu): reflective shadow maps per light, VPLs
// importance-sampled from RSM flux, extra bounces shot through the voxel scene, an interleaved KxK
// gather with SVO-restart visibility, a geometry-aware merge filter. Writes targets.indirect; the
// engine's lighting pass adds albedo x indirect to direct light. Stages: rsm, vpl_generate, vpl_bounce,
// indirect, filter (plus the voxel scene's voxelize and svo_build).
#include <algorithm>
#include <memory>

#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

enum class ManyLightsView { Final, Indirect, Vpls, SubImages };

struct ManyLightsSettings {
  uint32_t vplCount = 512;          // total over all bounces (per bounce: vplCount / bounces)
  uint32_t bounces = 1;             // 1..3
  uint32_t interleave = 4;          // K: the G-buffer is split into K x K sub-images
  float distanceClamp = 0.01f;      // B (world units^2): G = cos cos / max(B, d^2)
  float luminanceThreshold = 0.01f; // skip VPLs dimmer than this fraction of a first-bounce VPL
  uint32_t rsmResolution = 256;
  bool visibility = true;           // false: V = 1 (no indirect shadows), for comparisons
  float liftVoxels = 1.5f;          // segment ends leave their surface by this many voxels
  float filterPlaneTolerance = 0.02f;  // relative to the view distance
  uint32_t seed = 1;
  ManyLightsView view = ManyLightsView::Final;
};

struct VplReadback {
  glm::vec3 position;
  int bounce;        // -1: invalid
  glm::vec3 normal;
  glm::vec3 flux;
};

class ManyLights final : public render::RenderFeature {
 public:
  ManyLights(render::VulkanContext& ctx, VoxelScene& voxels, const ManyLightsSettings& settings = {});
  ~ManyLights() override;

  const char* name() const override { return "many_lights"; }
  void prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) override;
  bool record(render::FrameContext& frame) override;
  void recordAfterLighting(render::FrameContext& frame) override;
  void resize(render::VulkanContext& ctx, uint32_t width, uint32_t height) override;

  ManyLightsSettings& settings() { return settings_; }
  // VPLs per frame as used: the requested count rounded down to a multiple of the bounces.
  uint32_t vplCount() const {
    const uint32_t bounces = std::clamp(settings_.bounces, 1u, 3u);  // as prepare() will clamp them
    return std::max(1u, settings_.vplCount / bounces) * bounces;
  }
  // The current VPLs (read back; tests and tools).
  std::vector<VplReadback> readbackVpls();

 private:
  void ensureRsm(uint32_t layers);

  render::VulkanContext& ctx_;
  VoxelScene& voxels_;
  ManyLightsSettings settings_;
  uint32_t rsmLayers_ = 0, rsmLayersUsed_ = 0, perBounce_ = 0;
  render::Image rsmPosition_, rsmNormal_, rsmFlux_, rsmDepth_;
  render::Buffer layers_, lights_, rowPrefix_, rowCdf_, vpls_;
  render::Image raw_;
  // One RSM pipeline per material kind (base-colour texture or not), made on first use: lavapipe would
  // run the lookup of a branch not taken.
  render::Pipeline rsm_[2];
  render::Pipeline& rsmPipelineFor(bool baseColorTexture);
  render::Pipeline cdfRows_, cdfTotal_, sample_, bounce_, debug_;
  std::unique_ptr<class IndirectGatherPass> gatherPass_;
  std::unique_ptr<class IndirectFilterPass> filterPass_;
};

}  // namespace dyngi::gi
