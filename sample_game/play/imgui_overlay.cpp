#include "play/imgui_overlay.h"

#include <imgui.h>
#include <backends/imgui_impl_vulkan.h>

#include <cfloat>

#include "dyngi/engine/render/context.h"
#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/vk_common.h"

namespace dyngi::sample {
namespace {
void checkVk(VkResult r) {
  if (r != VK_SUCCESS) throw render::VulkanError("ImGui's Vulkan backend: VkResult " + std::to_string(int(r)));
}
constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;  // RenderTargets::ldr
}  // namespace

ImGuiOverlay::ImGuiOverlay(render::VulkanContext& ctx) : ctx_(ctx) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the same layout every run: scripted sessions find widgets where they were
  io.BackendFlags |= ImGuiBackendFlags_HasMouseCursors;
  ImGui::StyleColorsDark();

  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 16;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = sizes;
  DYNGI_VK(vkCreateDescriptorPool(ctx.device(), &pi, nullptr, &pool_));

  // One subpass on the display image: keep what tone mapping wrote, draw the panel over it.
  VkAttachmentDescription color{};
  color.format = kDisplayFormat;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 1;
  rp.pAttachments = &color;
  rp.subpassCount = 1;
  rp.pSubpasses = &sub;
  DYNGI_VK(vkCreateRenderPass(ctx.device(), &rp, nullptr, &renderPass_));

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = ctx.instance();
  init.PhysicalDevice = ctx.physicalDevice();
  init.Device = ctx.device();
  init.QueueFamily = ctx.queueFamily();
  init.Queue = ctx.queue();
  init.DescriptorPool = pool_;
  init.MinImageCount = 2;  // the renderer waits for every frame: two vertex buffers are plenty
  init.ImageCount = 2;
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkVk;
  if (!ImGui_ImplVulkan_Init(&init, renderPass_)) throw render::VulkanError("ImGui_ImplVulkan_Init failed");
  ctx.immediate([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiOverlay::~ImGuiOverlay() {
  vkDeviceWaitIdle(ctx_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui::DestroyContext();
  if (framebuffer_) vkDestroyFramebuffer(ctx_.device(), framebuffer_, nullptr);
  vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
  vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
}

void ImGuiOverlay::beginFrame(const InputFrame& input, uint32_t width, uint32_t height, double dt) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(width), float(height));
  io.DeltaTime = dt > 0.0 ? float(dt) : 1.0f / 60.0f;
  io.MousePos = input.mouse.x >= 0 ? ImVec2(float(input.mouse.x), float(input.mouse.y)) : ImVec2(-FLT_MAX, -FLT_MAX);
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = input.down[b];
  io.MouseWheel = float(input.scroll);
  ImGui_ImplVulkan_NewFrame();
  ImGui::NewFrame();
}

void ImGuiOverlay::endFrame() {
  ImGui::Render();
  wantsMouse_ = ImGui::GetIO().WantCaptureMouse;
  frameReady_ = true;
}

void ImGuiOverlay::ensureFramebuffer(const render::Image& ldr, uint32_t width, uint32_t height) {
  if (framebuffer_ && framebufferView_ == ldr.view()) return;
  if (framebuffer_) vkDestroyFramebuffer(ctx_.device(), framebuffer_, nullptr);
  VkImageView view = ldr.view();
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = 1;
  fi.pAttachments = &view;
  fi.width = width;
  fi.height = height;
  fi.layers = 1;
  DYNGI_VK(vkCreateFramebuffer(ctx_.device(), &fi, nullptr, &framebuffer_));
  framebufferView_ = view;
}

void ImGuiOverlay::recordOverlay(render::FrameContext& frame) {
  if (!frameReady_) return;  // no widgets this frame (headless without a panel)
  frameReady_ = false;
  ImDrawData* draw = ImGui::GetDrawData();
  if (!draw || draw->CmdListsCount == 0) return;
  render::RenderTargets& t = frame.targets;
  ensureFramebuffer(t.ldr, t.width, t.height);
  render::ScopedPass scope(frame.ctx, frame.timer, frame.cmd, "ui");
  t.ldr.transition(frame.cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                   VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  bi.renderPass = renderPass_;
  bi.framebuffer = framebuffer_;
  bi.renderArea = {{0, 0}, {t.width, t.height}};
  vkCmdBeginRenderPass(frame.cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(draw, frame.cmd);
  vkCmdEndRenderPass(frame.cmd);
  // Back to GENERAL, as every target is left after the pass that writes it.
  t.ldr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                   VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

}  // namespace dyngi::sample
