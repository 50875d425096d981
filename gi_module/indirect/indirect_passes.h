#pragma once
// The passes the VPL techniques share: the interleaved gather (shaders/gather.glsl) and the
// geometry-aware merge filter (shaders/filter_tent.glsl: filter_rows.comp, filter_columns.comp). A technique that needs more from the gather (the
// temporal technique accumulates inside it) brings its own gather shader built on gather.glsl and
// declares its extra bindings here; no technique binds images it does not use.
#include <functional>
#include <span>
#include <vector>

#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/gi/budget_controller.h"
#include "indirect/shaders/indirect_shared.h"

namespace dyngi::gi {

struct VplOptions;

class IndirectGatherPass {
 public:
  // The plain gather (gather.comp), or a technique's variant: a shader that includes gather.glsl, with
  // `extraBindings` from DYNGI_GATHER_FIRST_TECHNIQUE_BINDING and `extraPushBytes` after GatherPush.
  explicit IndirectGatherPass(render::VulkanContext& ctx);
  IndirectGatherPass(render::VulkanContext& ctx, render::ShaderCode variant, std::span<const render::Binding> extraBindings,
                     uint32_t extraPushBytes, const char* name);

  struct Inputs {
    VkBuffer vpls = VK_NULL_HANDLE;
    VkBuffer nodes = VK_NULL_HANDLE;  // the SVO (visibility 0); any valid buffer otherwise
    VkBuffer bits = VK_NULL_HANDLE;   // precomputed visibility (visibility 2); any valid buffer otherwise
    gpu::GatherPush push{};
    // A variant's own descriptors and push constants (after GatherPush).
    std::function<void(render::DescriptorWrites&)> extraWrites;
    const void* extraPush = nullptr;
  };
  // Gathers into `raw` (rgba32ui, filter_input.glsl's packing; "indirect" in stats).
  void record(render::FrameContext& frame, render::Image& raw, const Inputs& in);

 private:
  render::VulkanContext& ctx_;
  render::ShaderCode variant_;
  std::vector<render::Binding> bindings_;
  const char* name_;
  render::Pipeline pipeline_;
  render::Pipeline chunked_;  // kGatherChunked: made the first time a gather needs chunks
  uint32_t extraPushBytes_ = 0;
  render::Buffer clampSpread_;  // (I, N) per table sample (shaders/shared/clamp_spread.h)
};

class IndirectFilterPass {
 public:
  // Whether record() runs the clamp compensation with these options ("compensate" in stats).
  static bool compensates(const VplOptions& vpl);
  explicit IndirectFilterPass(render::VulkanContext& ctx);
  // Filters `input` (interleaved K x K, K in 1..8; rgba32ui packed as in filter_input.glsl) into
  // frame.targets.indirect ("filter" in stats): a separable geometry-aware tent (shaders/filter_tent.glsl),
  // with vpl.filterPlaneTolerance. Between its passes, unless vpl.clampCompensation or vpl.distanceClamp is
  // 0, it traces the light the gather's distance clamp dropped (shaders/compensate.comp, "compensate" in
  // stats: short screen-space rays for one pixel in 4 x 4), which the second pass adds.
  void record(render::FrameContext& frame, render::Image& input, uint32_t K, const VplOptions& vpl);

 private:
  void recordCompensation(render::FrameContext& frame, const VplOptions& vpl);

  render::VulkanContext& ctx_;
  // Per K, made on first use (K is a specialization constant): along rows, then columns (without and
  // with the compensation).
  render::Pipeline rows_[8], columns_[8][2], compensate_, compensateBlur_;
  render::Image rowsResult_;   // rgba32ui packed as the input (filter_input.glsl), the frame's size
  render::Image traced_, compensation_;  // one texel per DYNGI_COMPENSATE_SCALE^2 pixels, packed likewise: traced, blurred
};

// The VPL techniques' budget knob over the bounce tail's probes: the stride (VplOptions::bounceTailStride)
// from the user's to twice it, at most 4 (past that a few probes carry so much light that they show as
// hot spots). None with the tail off.
std::vector<QualityKnob> tailStrideKnob(const VplOptions& vpl, std::function<void(uint32_t)> setStride);

}  // namespace dyngi::gi
