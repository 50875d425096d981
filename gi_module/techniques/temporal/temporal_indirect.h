#pragma once
// Temporal indirect light from incremental VPL paths (the render side of VplPaths).
//
// Each frame one temporal set is gathered (a set whose VPLs changed first, else the one rendered
// longest ago; while some set holds no light, at the start or after a burst made sets stale, up to
// catchUpSets of them) with K x K interleaving and the chosen visibility: the SVO march on the GPU, or Embree
// on the CPU (this frame's G-buffer is read back mid-frame and the results are uploaded as bits). The
// result is kept per set with its depth and camera; every frame all sets are reprojected into the
// current view (samples whose surface moved more than the cut-off are dropped) and summed, then the
// geometry-aware filter (the discontinuity buffer) removes the interleaving pattern.
// Stages: indirect (the gather, which also stores the set and accumulates in O(1) the pixels whose
// camera and surface did not change), reproject (every set reprojected for the other pixels: those the
// gather queued, or all when the camera moved), filter; reduce and upsample around them when they run
// on a smaller screen (ReducedScreen: VplOptions::gatherScale, a GI budget's gather_fraction);
// the Embree visibility's CPU time is reported separately.
#include <algorithm>
#include <memory>
#include <vector>

#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/temporal_options.h"
#include "dyngi/gi/voxel_scene.h"
#include "techniques/temporal/vpl_paths.h"

namespace dyngi::gi {

namespace gpu {
struct AccumulatePush;
struct GpuVpl;
}

struct TemporalVpl {
  glm::vec3 position, normal;
  bool valid;
};

class TemporalIndirect final : public render::RenderFeature {
 public:
  // `voxels` is needed for Svo visibility, `bvh` for Bvh visibility. The options are the VPL paths'
  // (one TemporalOptions for the technique's CPU and render sides).
  TemporalIndirect(render::VulkanContext& ctx, VplPaths& paths, VoxelScene* voxels, const EmbreeScene* bvh);
  ~TemporalIndirect() override;

  const char* name() const override { return "temporal_indirect"; }
  void prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) override;
  bool record(render::FrameContext& frame) override;
  void resize(render::VulkanContext& ctx, uint32_t width, uint32_t height) override;

  TemporalOptions& settings() { return settings_; }
  const TemporalOptions& settings() const { return settings_; }
  VplPaths& paths() { return paths_; }
  uint32_t lastRenderedSet() const { return currentSet_; }
  uint32_t lastFrameSetCount() const { return uint32_t(frameSets_.size()); }  // sets gathered (more while catching up)
  // VPLs gathered per frame: a set's VPLs (VPLs / T) by default. Fewer (a GI budget's knob) gathers an
  // evenly spread subset of each set, standing for the whole set (GatherPush::estimatedCount: unbiased,
  // noisier).
  uint32_t setSize() const { return perSet_; }
  uint32_t vplsPerFrame() const { return gathered_; }
  void setVplsPerFrame(uint32_t count) { gathered_ = std::clamp(count, 1u, perSet_); }
  // How many times smaller a side the screen passes' screen is (ReducedScreen): VplOptions::gatherScale
  // times a GI budget's factor. A change restarts the sets' history (their images are remade at the new size).
  float gatherScale() const { return std::clamp(settings_.vpl.gatherScale * budgetGatherScale_, 1.0f, 8.0f); }
  void setBudgetGatherScale(float factor) { budgetGatherScale_ = std::max(1.0f, factor); }
  float budgetGatherScale() const { return budgetGatherScale_; }
  // The bounce tail gathers one probe in this many (VplOptions::bounceTailStride until a GI budget moves it).
  uint32_t tailStride() const { return tailStride_; }
  void setTailStride(uint32_t stride) { tailStride_ = std::max(1u, stride); }
  // Whether the screen passes run on a smaller screen (then "reduce" and "upsample" are timed).
  bool screenReduced() const;
  uint32_t setsRendered() const;  // sets rendered at least once
  // Sets gathered in one frame while some hold no light: TemporalOptions::catchUpSets, or one (a GI
  // budget spreads the catch-up over frames; the sets without light stay out of the average meanwhile).
  void setCatchUpOneSetAFrame(bool one) { maxSetsPerFrame_ = one ? 1u : std::clamp(settings_.catchUpSets, 1u, sets_); }
  double lastBvhVisibilityMs() const { return bvhMs_; }
  uint32_t lastTrappedVpls() const { return trappedVpls_; }  // left out this frame: a surface within the SVO lift

 private:
  void dropTrappedVpls(std::vector<gpu::GpuVpl>& gpuVpls);
  void computeBvhVisibility(render::FrameContext& frame, uint32_t perPixel);
  // The gather, the reprojection and the filter on `screen` (the frame's, or the reduced one).
  void recordScreen(render::FrameContext& screen);
  // The full reprojection (temporal_reproject.comp) of the pixels the gather queued, or of every pixel.
  void recordReprojection(render::FrameContext& frame, const gpu::AccumulatePush& push, bool queued);

  render::VulkanContext& ctx_;
  VplPaths& paths_;
  VoxelScene* voxels_;
  const EmbreeScene* bvh_;
  TemporalOptions settings_;  // a copy of the paths' options: tests switch accumulation modes on it
  uint32_t sets_ = 1, perSet_ = 1;
  uint32_t gathered_ = 1;  // of a set's perSet_ VPLs, how many are gathered (setVplsPerFrame)
  uint32_t slots_ = 1;     // per set gathered this frame: gathered_, then the bounce tail's probes (prepare)
  uint32_t currentSet_ = 0;
  uint64_t frameCounter_ = 0;
  std::vector<int64_t> lastRendered_;   // frame each set was last gathered (-1: never, or dropped as stale)
  bool droppedSets_ = false;            // this frame dropped a stale set (TemporalOptions::dropStaleSets)
  std::vector<uint32_t> frameSets_;     // the sets gathered this frame (one, or more while catching up)
  uint32_t maxSetsPerFrame_ = 1;        // TemporalOptions::catchUpSets
  std::vector<TemporalVpl> setVpls_;  // CPU copy of the VPLs uploaded this frame (every set gathered)
  render::Buffer vpls_, cameras_, bits_;
  // Per pixel (temporal_accumulate.glsl): each set's sample (one rg32ui layer a set: light, depth) and
  // the running sum with its depth and set count.
  render::Image setSamples_, sums_;
  render::Buffer queue_, queueArgs_;  // pixels queued for the full reprojection, and their count (TemporalQueue)
  render::Pipeline reprojectPipeline_;
  glm::mat4 lastCamera_{0.0f};
  render::Image accumulated_;  // the gather's accumulated light, the filter's input
  uint32_t interleave() const { return std::clamp(settings_.vpl.interleave, 1u, 8u); }  // K
  std::vector<glm::mat4> setCameras_;   // CPU copy: which sets were stored from the current camera
  std::unique_ptr<class IndirectGatherPass> gatherPass_;
  std::unique_ptr<class IndirectFilterPass> filterPass_;
  std::unique_ptr<class ReducedScreen> reduced_;
  float budgetGatherScale_ = 1.0f;
  uint32_t tailStride_ = 1;
  uint32_t width_ = 0, height_ = 0;  // the frame's (resize); the images are at the reduced size
  double bvhMs_ = 0.0;
  uint32_t trappedVpls_ = 0;
};

}  // namespace dyngi::gi
