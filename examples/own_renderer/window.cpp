#include "window.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "vulkan_host.h"

namespace host {

namespace {
void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(int(r)) + ")");
}
}  // namespace

std::vector<const char*> Window::instanceExtensions() {
  if (!glfwInit()) throw std::runtime_error("--window: no display (GLFW could not start; set DISPLAY)");
  if (!glfwVulkanSupported()) throw std::runtime_error("--window: GLFW finds no Vulkan loader");
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<const char*>(names, names + n);
}

Window::Window(VulkanHost& vk, uint32_t width, uint32_t height, const char* title) : vk_(vk), width_(width), height_(height) {
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);  // the G-buffer and the GI's images are made at --size
  window_ = glfwCreateWindow(int(width), int(height), title, nullptr, nullptr);
  if (!window_) throw std::runtime_error("--window: glfwCreateWindow failed");
  check(glfwCreateWindowSurface(vk_.instance(), window_, nullptr, &surface_), "glfwCreateWindowSurface");
  createSwapchain();
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  check(vkCreateSemaphore(vk_.device(), &sci, nullptr, &acquired_), "vkCreateSemaphore");
  rendered_.resize(images_.size());
  for (VkSemaphore& s : rendered_) check(vkCreateSemaphore(vk_.device(), &sci, nullptr, &s), "vkCreateSemaphore");
}

Window::~Window() {
  VkDevice d = vk_.device();
  vkDeviceWaitIdle(d);
  for (VkSemaphore s : rendered_) vkDestroySemaphore(d, s, nullptr);
  vkDestroySemaphore(d, acquired_, nullptr);
  vkDestroySwapchainKHR(d, swapchain_, nullptr);
  vkDestroySurfaceKHR(vk_.instance(), surface_, nullptr);
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::createSwapchain() {
  VkPhysicalDevice pd = vk_.physicalDevice();
  VkBool32 presentable = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(pd, vk_.external().queueFamily, surface_, &presentable);
  if (!presentable) throw std::runtime_error("--window: the device's queue cannot present to this window");
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT)) throw std::runtime_error("--window: the swapchain cannot be a blit target");
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, formats.data());
  if (formats.empty()) throw std::runtime_error("--window: the surface has no formats");
  // UNORM: the display image is already sRGB-encoded, and a blit into an sRGB image would encode it again.
  format_ = formats[0].format;
  VkColorSpaceKHR space = formats[0].colorSpace;
  for (const VkSurfaceFormatKHR& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) format_ = f.format, space = f.colorSpace;
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount) ci.minImageCount = std::min(ci.minImageCount, caps.maxImageCount);
  ci.imageFormat = format_;
  ci.imageColorSpace = space;
  ci.imageExtent = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent : VkExtent2D{width_, height_};
  extent_ = ci.imageExtent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always there
  ci.clipped = VK_TRUE;
  check(vkCreateSwapchainKHR(vk_.device(), &ci, nullptr, &swapchain_), "vkCreateSwapchainKHR");
  vkGetSwapchainImagesKHR(vk_.device(), swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(vk_.device(), swapchain_, &n, images_.data());
}

bool Window::open() const { return !glfwWindowShouldClose(window_); }

void Window::poll() { glfwPollEvents(); }

void Window::present(VkImage display, const std::function<void(VkCommandBuffer)>& record) {
  uint32_t index = 0;
  const VkResult acquired = vkAcquireNextImageKHR(vk_.device(), swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR) {
    vk_.submit(record);  // no image this frame (the surface changed): the frame still runs, unseen
    return;
  }
  vk_.submit(
      [&](VkCommandBuffer cmd) {
        record(cmd);
        recordBlit(cmd, display, index);
      },
      acquired_, rendered_[index]);
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  vkQueuePresentKHR(vk_.queue(), &pi);  // OUT_OF_DATE: the window cannot resize, so the next acquire says
}

void Window::recordBlit(VkCommandBuffer cmd, VkImage display, uint32_t index) const {
  auto barrier = [&](VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                     VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.imageMemoryBarrierCount = 1;
    di.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &di);
  };
  // The acquire semaphore is waited at the transfer stage: the layout change waits there too.
  barrier(images_[index], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
          VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  barrier(display, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
          VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkImageBlit region{};
  region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffsets[1] = {int32_t(width_), int32_t(height_), 1};
  region.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
  const VkFilter filter = extent_.width == width_ && extent_.height == height_ ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  vkCmdBlitImage(cmd, display, VK_IMAGE_LAYOUT_GENERAL, images_[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, filter);
  barrier(images_[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0);
}

}  // namespace host
