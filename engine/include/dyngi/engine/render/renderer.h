#pragma once
// The deferred renderer: shadow -> gbuffer -> [render features] -> lighting (direct + albedo x indirect)
// -> [features after lighting] -> tonemap
// -> present or read back. One frame in flight: the CPU waits for each frame's fence. On lavapipe the
// "GPU" is the CPU, so overlap would buy nothing there; on a discrete GPU this is the first thing to
// change (see docs/ARCHITECTURE.md).
#include <chrono>
#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/render/render_feature.h"
#include "dyngi/engine/render/swapchain.h"

namespace dyngi::render {

class ShadowPass;
class GBufferPass;
class LightingPass;
class TonemapPass;

struct RendererSettings {
  uint32_t shadowMapSize = 1024;
  uint32_t maxShadowLayers = 24;   // a spot or directional light takes 1 layer, a point light 6
  float exposure = 1.0f;           // linear multiplier applied before tone mapping
  int toneMapper = 0;              // 0 ACES fit, 1 clamp (for tests that compare linear values)
  glm::vec3 background{0.0f};      // radiance where no geometry is hit
  bool gpuTimestamps = true;  // time the passes (FrameStats::gpuMs), as stageTiming says
  // Timestamps cost nothing, but on a device that runs on the CPU (lavapipe) they do not bracket compute
  // dispatches: VCT's cone trace read 0.9 ms there and cost about 20. Fenced submits and waits for the
  // frame's commands at every pass boundary and times each pass by the CPU clock: every pass' own cost,
  // in a frame that loses the overlap between passes (benchmarks; the present blit is not timed).
  GpuTimer::Mode stageTiming = GpuTimer::Mode::Timestamps;
  // Run only the render features (no shadow/G-buffer/lighting/tone map): for compute-only work such as
  // benchmarks of a feature.
  bool featuresOnly = false;
};

enum class TargetId { Position, Normal, Albedo, Emissive, Depth, Indirect, Specular, Hdr, Ldr };

struct FrameStats {
  std::vector<std::pair<std::string, double>> gpuMs;  // per pass, recording order
  // A fenced frame's timestamps of the same passes, where the device has them (GpuTimer::timestampResults).
  std::vector<std::pair<std::string, double>> gpuMsTimestamps;
  double cpuRecordMs = 0;   // building uploads and recording commands
  double cpuWaitMs = 0;     // waiting for the frame's fence
  bool presented = false;
};

class Renderer {
 public:
  Renderer(VulkanContext& ctx, const RendererSettings& settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Creates the screen-sized targets. A 0x0 size is refused (keep the previous targets).
  bool resize(uint32_t width, uint32_t height);
  uint32_t width() const { return targets_.width; }
  uint32_t height() const { return targets_.height; }

  // Features record in the order added; the renderer does not own them. A feature added after
  // resize() is sized at once.
  void addFeature(RenderFeature* feature) {
    features_.push_back(feature);
    if (targets_.width) feature->resize(ctx_, targets_.width, targets_.height);
  }
  // Takes a feature out (a subsystem switching what it records). Between frames only: render() has
  // waited for its fence, so nothing the feature recorded is still in flight.
  void removeFeature(RenderFeature* feature) { std::erase(features_, feature); }

  // Renders one frame; when `swapchain` is given (and valid) the result is presented to it.
  const FrameStats& render(const RenderSnapshot& snapshot, Swapchain* swapchain = nullptr);
  const FrameStats& lastStats() const { return stats_; }
  // How the passes are timed from the next frame on (RendererSettings::stageTiming); nothing when the
  // renderer times nothing (gpuTimestamps off). Fenced is refused once a host records its frames.
  std::optional<GpuTimer::Mode> stageTiming() const { return timer_ ? std::optional(timer_->mode()) : std::nullopt; }
  void setStageTiming(GpuTimer::Mode mode);
  // A host records the frames (recordHostFrame): they cannot be fenced.
  bool hostRecordsFrames() const { return hostFramePending_; }

  // A host's frame (gi::GiContext): the shadow maps and the features recorded into `cmd`, a command
  // buffer the host submits. `fillGBuffer` writes the G-buffer targets (after the shadow maps),
  // `afterFeatures` takes what the features wrote; nothing is lit or tone-mapped, and nothing here
  // waits on the device. The previous host frame's pass times and features' frameFinished() come first:
  // the host has waited for it (one frame in flight); lastStats().gpuMs are that frame's.
  const FrameStats& recordHostFrame(const RenderSnapshot& snapshot, VkCommandBuffer cmd, const std::function<void(FrameContext&)>& fillGBuffer,
                                    const std::function<void(FrameContext&)>& afterFeatures);

  // A target's view (GENERAL layout after the frame that wrote it): a host reads the GI's own outputs.
  VkImageView targetView(TargetId id) { return target(id).view(); }
  Image& targetImage(TargetId id) { return target(id); }

  // Reads a target of the last frame back as RGBA floats (8-bit targets come back in 0..1).
  std::vector<glm::vec4> readback(TargetId target);
  // The display image as RGBA8 bytes, row-major, top row first.
  std::vector<uint8_t> readbackLdr();

  RendererSettings& settings() { return settings_; }
  VulkanContext& context() { return ctx_; }
  RenderTargets& targets() { return targets_; }

 private:
  void create();
  void releaseHandles();
  GpuMesh* meshFor(const scene::AssetStore& assets, scene::MeshId id);
  // render()'s steps, in order.
  std::vector<GpuMesh*> uploadAssets(const RenderSnapshot& snapshot);
  gpu::FrameUniforms uploadFrameUniforms(const RenderSnapshot& snapshot);
  void beginCommands();
  void submitAndWaitMidFrame();
  void recordPasses(FrameContext& frame, const std::function<VkImageView(scene::TextureId)>& textures);
  void clearIndirectIfUnwritten(VkCommandBuffer cmd, bool written);
  bool hostFramePending_ = false;  // a host frame was recorded: its times and frameFinished() come next
  void recordPresentBlit(Swapchain& swapchain, uint32_t imageIndex);
  void submitFrame(Swapchain* swapchain, uint32_t imageIndex, std::chrono::steady_clock::time_point recordStart);
  VkImageView textureView(const scene::AssetStore& assets, scene::TextureId id);
  Image& target(TargetId id);

  VulkanContext& ctx_;
  RendererSettings settings_;
  RenderTargets targets_;
  std::unordered_map<scene::MeshId, GpuMesh> meshes_;
  const scene::AssetStore* meshesOf_ = nullptr;  // caches are per asset store
  std::unordered_map<scene::TextureId, Image> textures_;
  Image whiteTexture_;
  Buffer frameUniforms_;
  Buffer drawInstances_;           // frameInstances_.records
  FrameInstances frameInstances_;  // rebuilt every frame
  VkSampler linearSampler_ = VK_NULL_HANDLE;
  VkSampler nearestSampler_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::unique_ptr<GpuTimer> timer_;
  std::unique_ptr<ShadowPass> shadow_;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<LightingPass> lighting_;
  std::unique_ptr<TonemapPass> tonemap_;
  std::vector<RenderFeature*> features_;
  FrameStats stats_;
};

}  // namespace dyngi::render
