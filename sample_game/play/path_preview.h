#pragma once
// --gi path in a window: a progressive preview of the reference path tracer. Each frame adds samples
// (one per pixel, a new seed) to a running mean on the CPU and shows it in place of the rasterized
// frame (the HDR target, before tone mapping and the panel). Anything that changes the picture (the
// camera, a draw's transform or material, a light) starts the mean over.
#include <memory>

#include "dyngi/engine/render/render_feature.h"
#include "dyngi/engine/render/resources.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/gi/path_tracer.h"

namespace dyngi::sample {

class PathPreview final : public render::RenderFeature {
 public:
  // `bvh` follows the world (a BvhSyncSystem in the run's scheduler).
  PathPreview(const gi::EmbreeScene& bvh, const scene::AssetStore& assets, const gi::PathTracerSettings& settings);
  const char* name() const override { return "path_preview"; }
  void prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) override;
  bool record(render::FrameContext&) override { return false; }
  void recordAfterLighting(render::FrameContext& frame) override;
  void resize(render::VulkanContext&, uint32_t width, uint32_t height) override;
  uint32_t samplesPerPixel() const { return spp_; }

 private:
  const gi::EmbreeScene& bvh_;
  const scene::AssetStore& assets_;
  gi::PathTracerSettings settings_;
  uint32_t width_ = 0, height_ = 0;
  std::vector<glm::vec4> sum_;  // radiance summed over spp_ samples per pixel
  uint32_t spp_ = 0;
  std::unique_ptr<render::Buffer> staging_;
  // What the mean was traced from: a change starts it over.
  glm::mat4 view_{0.0f};
  std::vector<glm::mat4> models_;
  std::vector<glm::vec4> materials_;
  std::vector<glm::vec4> lights_;
};

}  // namespace dyngi::sample
