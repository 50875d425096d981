#pragma once
// A VPL technique's screen passes (the gather, the merge filter, the temporal sets) on a screen `scale`
// times smaller a side (any scale >= 1), the cheapest of a GI budget's knobs per unit of image lost: the
// gather's cost is per pixel. begin() makes a frame whose G-buffer holds, for each reduced pixel, the
// full-resolution pixel under its centre, and whose uniforms describe the smaller screen (so every
// screen pass runs unchanged on it); finish() brings the light they wrote back to every pixel with a
// depth- and normal-aware upsample.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/gi/budget_controller.h"

namespace dyngi::gi {

class ReducedScreen {
 public:
  explicit ReducedScreen(render::VulkanContext& ctx) : ctx_(ctx) {}
  // The reduced screen's side for a full side (at least 1).
  static uint32_t reducedSize(uint32_t full, float scale) {
    return std::max(1u, uint32_t(std::lround(double(full) / std::max(1.0, double(scale)))));
  }
  // Whether a width x height frame at `scale` gets a smaller screen (begin() then reduces it).
  static bool reduces(uint32_t width, uint32_t height, float scale) {
    return reducedSize(width, scale) != width || reducedSize(height, scale) != height;
  }

  // The frame the screen passes record into: `frame` itself at scale 1; otherwise the reduced frame,
  // after recording the G-buffer's reduction ("reduce" in stats). Its targets.indirect is where the
  // screen passes leave their light.
  render::FrameContext& begin(render::FrameContext& frame, float scale);
  // At a scale above 1: the reduced frame's indirect light to every pixel of frame.targets.indirect
  // ("upsample" in stats).
  void finish(render::FrameContext& frame);

 private:
  void makeTargets(uint32_t width, uint32_t height);

  render::VulkanContext& ctx_;
  glm::vec2 scale_{1.0f};  // full over reduced size, per axis
  render::RenderTargets targets_;  // position, normal, albedo, emissive, indirect; the others unused
  render::Buffer uniformBuffer_;
  ::dyngi::gpu::FrameUniforms uniforms_{};
  std::optional<render::FrameContext> frame_;
  render::Pipeline reduce_, upsample_;
};

// The uniforms of the screen `scale` times smaller a side: its size, and pixel rays through each reduced
// pixel's centre (the full-resolution point (q + 0.5) x full size / reduced size). The projection is the
// frame's: in NDC both screens are the same.
::dyngi::gpu::FrameUniforms reducedUniforms(const ::dyngi::gpu::FrameUniforms& full, float scale);

// The VPL techniques' budget knob over it: the fraction of pixels the screen passes run on, from 1 down
// to 1/16 in steps of 15 percent, handed to `setFactor` as the scale factor (1 .. 4) over
// VplOptions::gatherScale.
QualityKnob gatherFractionKnob(std::function<void(float)> setFactor);

}  // namespace dyngi::gi
