#pragma once
// The views every technique has, drawn by the GI system rather than by each technique: `indirect`, the
// GI's indirect diffuse light (targets.indirect, E / pi) over the HDR image, after the lighting pass.
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/render_feature.h"

namespace dyngi::gi {

class GiIndirectView final : public render::RenderFeature {
 public:
  explicit GiIndirectView(render::VulkanContext& ctx);
  const char* name() const override { return "gi_indirect_view"; }
  bool record(render::FrameContext&) override { return false; }
  void recordAfterLighting(render::FrameContext& frame) override;
  bool enabled = false;

 private:
  render::VulkanContext& ctx_;
  render::LazyPipeline pipeline_;  // made on first use: a debug view
};

}  // namespace dyngi::gi
