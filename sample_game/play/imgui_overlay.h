#pragma once
// Dear ImGui drawn over the display image (a RenderFeature's overlay: after tone mapping, so the panel
// is in the presented frame and in readbackLdr, and the 3D view under it is untouched elsewhere).
// Input comes from an InputFrame, the window's or an input script's, the same way in both: a scripted
// session clicks the same widgets a person does. No keyboard text entry: values change by dragging.
#include <cstdint>

#include <vulkan/vulkan.h>

#include "dyngi/engine/render/render_feature.h"
#include "play/input.h"

namespace dyngi::sample {

class ImGuiOverlay final : public render::RenderFeature {
 public:
  explicit ImGuiOverlay(render::VulkanContext& ctx);
  ~ImGuiOverlay() override;
  ImGuiOverlay(const ImGuiOverlay&) = delete;
  ImGuiOverlay& operator=(const ImGuiOverlay&) = delete;

  const char* name() const override { return "ui"; }
  bool record(render::FrameContext&) override { return false; }
  void recordOverlay(render::FrameContext& frame) override;

  // A frame of widgets: begin, build them with ImGui calls, end (before the renderer renders).
  void beginFrame(const InputFrame& input, uint32_t width, uint32_t height, double dt);
  void endFrame();
  // Whether the last frame's widgets took the mouse (the scene then ignores it).
  bool wantsMouse() const { return wantsMouse_; }

 private:
  void ensureFramebuffer(const render::Image& ldr, uint32_t width, uint32_t height);

  render::VulkanContext& ctx_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkImageView framebufferView_ = VK_NULL_HANDLE;  // the ldr view the framebuffer was made for
  bool frameReady_ = false;                       // endFrame() ran since the last overlay
  bool wantsMouse_ = false;
};

}  // namespace dyngi::sample
