#pragma once
// Voxel cone tracing (after Crassin et al. 2011, "Interactive Indirect Illumination Using Voxel Cone
// Tracing"): the voxel scene's occupied voxels get the direct light they reflect and their emission
// (radiance injection, shadowed through the renderer's shadow maps; emissive surfaces' light from points
// sampled on them, shadowed through the SVO: VctOptions::emitterSamples), a 3D mip chain filters it
// (isotropic, or per direction), optional extra bounces cone-trace over the occupied voxels (each frame,
// or a part of them a frame, carried across frames: VctOptions::bounceFrames), and the
// screen traces diffuse cones (indirect light and ambient occlusion) and a specular cone per pixel,
// upsampled with a depth- and normal-aware filter. The trace may be spread over 2 or 4 frames, the pixels
// not traced in a frame reprojected from the last. Writes targets.indirect and targets.specular.
// Stages: inject, mips, bounce, trace (with reproject), filter, upsample (plus the voxel scene's
// voxelize and svo_build).
#include <algorithm>
#include <optional>
#include <vector>

#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/gi/vct_options.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi::gpu {
struct VctEmitterPoint;
}

namespace dyngi::gi {

struct VctFrameStats {
  bool injected = false;    // radiance injected this frame (every frame while the technique runs)
  double radianceUpdated = 0.0;  // the share of the voxels' radiance updated this frame (1/parts when spread)
  uint64_t clearedVoxels = 0;  // of level 0, cleared first: the stale boxes' (their emptied voxels zeroed), or all of them (res^3)
  uint32_t traceWidth = 0, traceHeight = 0;  // the resolution cones were traced at
  double tracedFraction = 1.0;  // of those, the share traced this frame (the rest reprojected)
  uint64_t volumeBytes = 0;  // radiance volumes, all levels
  bool specularCones = false;  // some draw is smoother than VctOptions::specularConeBelow: the trace marches specular cones
  double carriedUpdated = 0.0;  // the share of the voxels whose carried light (bounce or emitter light) was updated this frame
};

class VoxelConeTracing final : public render::RenderFeature {
 public:
  VoxelConeTracing(render::VulkanContext& ctx, VoxelScene& voxels, const VctOptions& options = {});
  ~VoxelConeTracing() override;

  const char* name() const override { return "vct"; }
  static std::vector<const char*> timedSections() { return {"inject", "mips", "bounce", "trace", "filter", "upsample"}; }
  bool record(render::FrameContext& frame) override;
  void recordAfterLighting(render::FrameContext& frame) override;

  VctOptions& settings() { return options_; }
  const VctOptions& settings() const { return options_; }
  const VctFrameStats& stats() const { return stats_; }
  // The trace resolution divisor in use: the options' (or the automatic one for the render size) times a
  // GI budget's factor, at most kMaxTraceScale.
  uint32_t traceScale() const;
  // 1 at the unit step: the cone passes' variant without a pow() a step (vct_cone.glsl's kVctUnitStep);
  // 0 at any other step.
  uint32_t unitStep() const { return options_.coneStep == 1.0f ? 1u : 0u; }
  // `options` as this feature uses them: counts and frames in their ranges, the cone interleave 1 without
  // the diffuse filter (nothing would bring the rows' cone sets together).
  static VctOptions validated(VctOptions options);
  // Drops the traced pixels' values kept from earlier frames (traceFrames > 1): the next frame uses only
  // what it traces, every pixel. For changes that make them wrong at once: a light switched, an emission
  // changed, a jump (VctTechnique::update decides).
  void dropTraceHistory() { traceHistory_ = false; }
  // The bounce light the voxels carry (VctOptions::bounceFrames) is cleared before the next injection and
  // that frame's pass updates every voxel, not its part: after a light switched or jumped none of the old
  // light stays, and the new light's first bounce is there at once. Under a GI budget
  // (setSpreadTraceWithoutHistory) the pass keeps to its part: the bounce light comes back part by part.
  // The emitters' light (VctOptions::emitterSamples) does not depend on the lights: it is kept.
  void refreshCarriedLight() { carriedWhole_ = carriedWhole_ || options_.bounceFrames > 0; }
  // The points on the emissive surfaces (DYNGI_VCT_EMITTER_POINTS, or none) whose light the voxels take
  // (VctOptions::emitterSamples, without carried bounce light). Other points than last frame's (an
  // emitter moved, switched or recoloured) update every voxel's emitter light at once.
  void setEmitterPoints(const std::vector<gpu::VctEmitterPoint>& points);
  // The voxels' carried light is the emitters' (not the cones' bounce light).
  bool carriesEmitterLight() const { return options_.bounceFrames == 0 && options_.emitterSamples > 0 && !lastEmitterPoints_.empty(); }
  // Frames over which every voxel's carried light is updated once: bounceFrames, or emitterFrames for
  // the emitters' light.
  uint32_t carriedFrames() const { return options_.bounceFrames > 0 ? options_.bounceFrames : options_.emitterFrames; }
  // A GI budget's slowdown of the carried light's update: each voxel's turn comes every bounceFrames x
  // this frames, and from 2 a moved object's new voxels wait for theirs (their update each frame is most
  // of the pass while something moves).
  void setBudgetCarriedSlowdown(uint32_t factor) { budgetCarriedSlowdown_ = std::max(factor, 1u); }
  uint32_t budgetCarriedSlowdown() const { return budgetCarriedSlowdown_; }
  // While a GI budget holds: a frame without trace history (the first, after a drop, new trace targets)
  // traces its share of the pixels as any other, and the upsample fills the rest from the pixels traced
  // (every 2 x 2 window holds one); the others get theirs over the next traceFrames - 1 frames.
  void setSpreadTraceWithoutHistory(bool spread) { spreadWithoutHistory_ = spread; }
  void setBudgetScaleFactor(uint32_t factor) { budgetFactor_ = std::max(factor, 1u); }
  uint32_t budgetScaleFactor() const { return budgetFactor_; }
  // The radiance update spread over this many frames (1 to 4; VctOptions::radianceFrames, or a GI
  // budget's more): each frame injects and mips one part of the voxels (vct_parts.glsl), so a light's
  // change reaches every voxel that many frames later; a frame whose SVO build changed voxels updates
  // the changed boxes too, and the first frame everything.
  void setBudgetRadianceParts(uint32_t parts) { budgetRadianceParts_ = std::clamp(parts, 1u, 4u); }
  uint32_t radianceParts() const;
  static constexpr uint32_t kMaxTraceScale = 8;
  static constexpr uint32_t kAutoTracePixels = 192 * 192;  // traceScale 0: the most pixels traced

  // For tests and tools: level 0 with its isotropic mip chain, the six-direction atlas (anisotropic),
  // this frame's injected direct radiance, the carried bounce light. Valid after the first frame.
  render::Image& radianceVolume() { return radiance_; }
  render::Image& anisotropicVolume() { return aniso_; }
  render::Image& directVolume() { return direct_; }
  render::Image& carriedVolume() { return carried_; }  // VctOptions::bounceFrames over 0, or emitter light
  // Marches one cone per ray (voxel units: origin, direction) through the volume as it stands, on the
  // GPU (vct_cone_probe.comp): rgb radiance, a opacity. Synchronous.
  std::vector<glm::vec4> probeCones(const std::vector<std::pair<glm::vec3, glm::vec3>>& rays, float tanHalf);

 private:
  // Pipeline variants by what they are for (specialization constants: lavapipe runs both sides of a
  // branch, so each is a pipeline of its own).
  struct ConeVariant {  // the passes that march cones over the voxels: bounce, probe
    bool anisotropic = false, unitStep = false;
    uint32_t index() const { return (anisotropic ? 1u : 0u) + (unitStep ? 2u : 0u); }
  };
  struct TraceVariant {
    bool anisotropic = false, specular = false, unitStep = false;
    uint32_t index() const { return (anisotropic ? 1u : 0u) + (specular ? 2u : 0u) + (unitStep ? 4u : 0u); }
  };
  enum class MipsVariant : uint32_t { Isotropic, Atlas, IsotropicOpaqueAxis, AtlasFromLevel0, AtlasFromDirect, Count };
  ConeVariant coneVariant() const { return {options_.anisotropic, unitStep() == 1}; }
  const render::Pipeline& mips(MipsVariant v) const { return mips_[uint32_t(v)].get(); }
  VkImageView anisoView() const { return options_.anisotropic ? aniso_.view() : radiance_.view(); }  // bound either way

  // The traced pixels, this frame's and last (alternating): diffuse (AO in alpha), specular (alpha: frames
  // since traced; both alphas -1: missing), the surface each saw (vct_reproject.comp's record).
  struct TracedPixels {
    render::Image diffuse, specular, surface;
  };
  // This frame's trace: its scale, the frames it is spread over and this frame's phase among them, the
  // images it writes and last frame's, whether some pixel marches a specular cone.
  struct TraceFrame {
    uint32_t scale = 1, frames = 1, phase = 0;
    // A quarter of the lattice traced with nothing carried over (a budget's spread, setSpreadTraceWithoutHistory):
    // its rows pair up over the cone set and the filter doubles its reach, to see as many cones as usual.
    bool quarterWithoutHistory = false;
    const TracedPixels* current = nullptr;
    const TracedPixels* lastFrame = nullptr;
    bool glossy = false;
  };

  void createLeafPipelines();
  void createMipsPipelines();
  void createScreenPipelines();
  void createSampler();
  // The part of the voxels a frame's radiance update covers (vct_parts.glsl): part of parts, and the
  // first boxCount changed boxes (changedBoxes_) of a frame whose SVO build changed voxels.
  struct RadiancePart {
    uint32_t part = 0, parts = 1, boxCount = 0;
  };
  static constexpr uint32_t kMaxChangedBoxes = 32;  // more: the frame updates everything
  // What a frame's radiance passes start from: `clearAll`, inject clears the whole volume first, so
  // everything must be written; else the boxes where this frame's SVO build changed voxels, uploaded
  // once to changedBoxes_ (uploadChangedBoxes).
  struct VolumeChange {
    bool clearAll = false;
    std::optional<uint32_t> changedBoxes{0u};
  };
  VolumeChange planVolumeChange();
  // This frame's part (everything unless spread), with the changed boxes.
  RadiancePart planRadianceUpdate(const VolumeChange& change);
  bool clearsEverything() const;
  void prepareFrame(render::FrameContext& frame);
  void recordInject(render::FrameContext& frame, RadiancePart part, const VolumeChange& change);
  void recordBounces(render::FrameContext& frame, const VolumeChange& change);
  // This frame's part of the carried light's update (carriedFrames), or every voxel after a refresh or
  // when the volume was cleared; with the voxels the SVO build added unless a budget slows it.
  RadiancePart planCarriedUpdate(const VolumeChange& change);
  void recordEmitterLight(VkCommandBuffer cmd, const VolumeChange& change);
  // The boxes where this frame's SVO build changed voxels into changedBoxes_: their count (0 without a
  // build), none when there are more than kMaxChangedBoxes.
  std::optional<uint32_t> uploadChangedBoxes();
  TraceFrame beginTrace(const render::FrameContext& frame);
  void recordTrace(render::FrameContext& frame, const TraceFrame& trace);
  void recordReproject(render::FrameContext& frame, const TraceFrame& trace);
  const render::Image& recordFilter(render::FrameContext& frame, const TraceFrame& trace);
  void recordUpsample(render::FrameContext& frame, const TraceFrame& trace, const render::Image& diffuse);
  void ensureVolumes(uint32_t res);
  void ensureTraceTargets(uint32_t width, uint32_t height);
  // The mip chain, or the anisotropic atlas. levelZeroIsDirect: level 0 holds the direct radiance (no
  // bounce added yet), which the atlas' first level then reads alone (vct_mips.comp, kSeenInSource).
  void recordMips(VkCommandBuffer cmd, bool levelZeroIsDirect, RadiancePart part);
  // Where voxels may have been emptied this frame (VoxelScene::staleBoxes), or everywhere.
  struct StaleVoxels {
    bool everywhere = false;
    std::vector<VoxelBox> boxes;
  };
  // Zeroes what the voxels that emptied held (in radiance level 0, the direct radiance, the atlas):
  // everything, or within the boxes (vct_clear_stale.comp for the voxels and the atlas' levels 0 and 1,
  // at the cells that emptied since the last build; the atlas' coarser levels whole, the mips rewriting
  // every occupied texel). Returns the voxels of level 0 covered.
  uint64_t recordClearStale(VkCommandBuffer cmd, const StaleVoxels& stale);
  void recordLeafPass(VkCommandBuffer cmd, const render::Pipeline& pipeline, const void* push, uint32_t pushBytes,
                      render::DescriptorWrites& writes);
  template <class Push>
  void fillConeParams(Push& p) const;

  render::VulkanContext& ctx_;
  VoxelScene& voxels_;
  VctOptions options_;
  uint32_t budgetFactor_ = 1;
  uint32_t budgetRadianceParts_ = 1;
  uint64_t partFrame_ = 0;  // radiance updates spread over parts so far: the next part
  uint32_t width_ = 0, height_ = 0;  // the render size the trace scale was chosen for
  uint32_t res_ = 0;
  uint64_t frames_ = 0;  // injected into the volumes as they stand (0: clear them first)
  render::SpecularSource specularSource_ = render::SpecularSource::None;  // this frame's (record())
  glm::vec3 historyOrigin_{0.0f};  // the volume last frame's radiance was injected into
  float historyVoxelSize_ = 0.0f;
  render::Image radiance_;     // res^3, full mip chain
  render::Image aniso_;        // 6 (res/2) x res/2 x res/2, mips (anisotropic only)
  render::Image direct_;       // res^3: the injected radiance, blended in place with last frame's (temporal blending); alpha: which cones see the voxel (vct_seen.glsl)
  render::Image bounced_;      // res^3: a bounce's output before it is committed to radiance_ level 0
  render::Image carried_;      // res^3: the bounce light each voxel carries (VctOptions::bounceFrames), or its emitter light
  render::Buffer emitterPoints_;  // gpu::VctEmitterPoint[DYNGI_VCT_EMITTER_POINTS]: setEmitterPoints
  std::vector<glm::vec4> lastEmitterPoints_;  // the points as uploaded, three vec4 each
  bool emittersSeen_ = false;  // some frame had emitter points: carried_ stays allocated
  uint32_t emitterFramesLeft_ = 0;  // frames of the emitter light's turn still to come (recordEmitterLight)
  uint64_t carriedFrame_ = 0;  // carried-light passes so far: the next part
  bool carriedWhole_ = false;  // refreshCarriedLight
  uint32_t budgetCarriedSlowdown_ = 1;
  render::Buffer staleRuns_;   // this frame's runs of cells vct_clear_stale.comp visits (recordClearStale)
  render::Buffer changedBoxes_;  // kMaxChangedBoxes (min, max) uvec4 pairs: uploadChangedBoxes
  TracedPixels traced_[2];
  render::Image filterAlongX_;     // the diffuse filter's first pass (along x)
  render::Image filteredDiffuse_;  // its second: what the upsample reads
  uint32_t tracedScale_ = 0;       // the trace scale traced_ was made for
  uint32_t tracedCurrent_ = 0;     // traced_[tracedCurrent_] is this frame's
  uint64_t traceFrame_ = 0;        // frames traced: the phase of the trace spread over frames
  bool traceHistory_ = false;      // traced_[last] holds last frame's pixels, valid to reproject
  bool spreadWithoutHistory_ = false;  // setSpreadTraceWithoutHistory
  glm::mat4 previousViewProj_{1.0f};
  VkSampler sampler_ = VK_NULL_HANDLE;
  render::Pipeline inject_, clearStale_, commit_, reproject_, filter_, emitterLight_;
  render::LazyPipeline mips_[uint32_t(MipsVariant::Count)], bounce_[4], carry_[4], probe_[4], trace_[8];  // by MipsVariant, ConeVariant, TraceVariant
  render::LazyPipeline upsample_[2], debug_[2];  // [specular image written], [anisotropic]
  VctFrameStats stats_;
};

}  // namespace dyngi::gi
