#include "dyngi/engine/render/swapchain.h"

#include <algorithm>

namespace dyngi::render {

Swapchain::Swapchain(VulkanContext& ctx, VkSurfaceKHR surface) : ctx_(ctx), surface_(surface) {
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface, &supported);
  if (!supported) {
    vkDestroySurfaceKHR(ctx.instance(), surface, nullptr);
    surface_ = VK_NULL_HANDLE;
    throw VulkanError("the Vulkan device cannot present to this window");
  }
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  try {  // the surface is ours from here on: release it and any semaphore made if a step fails
    DYNGI_VK(vkCreateSemaphore(ctx.device(), &sci, nullptr, &acquired_));
    DYNGI_VK(vkCreateSemaphore(ctx.device(), &sci, nullptr, &rendered_));
  } catch (...) {
    release();
    throw;
  }
}

Swapchain::~Swapchain() { release(); }

void Swapchain::release() {
  vkDeviceWaitIdle(ctx_.device());
  destroySwapchain();
  if (acquired_) vkDestroySemaphore(ctx_.device(), acquired_, nullptr);
  if (rendered_) vkDestroySemaphore(ctx_.device(), rendered_, nullptr);
  if (surface_) vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
  acquired_ = rendered_ = VK_NULL_HANDLE;
  surface_ = VK_NULL_HANDLE;
}

void Swapchain::destroySwapchain() {
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
  images_.clear();
}

bool Swapchain::recreate(uint32_t width, uint32_t height) {
  vkDeviceWaitIdle(ctx_.device());
  VkSurfaceCapabilitiesKHR caps;
  DYNGI_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physicalDevice(), surface_, &caps));
  VkExtent2D ext = caps.currentExtent;
  if (ext.width == UINT32_MAX) {
    ext.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    ext.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (ext.width == 0 || ext.height == 0 || width == 0 || height == 0) {
    destroySwapchain();
    return false;
  }
  uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physicalDevice(), surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(ctx_.physicalDevice(), surface_, &n, formats.data());
  // The tone-map pass already encodes sRGB, so the swapchain must be UNORM (no second encode).
  VkSurfaceFormatKHR chosen = formats.empty() ? VkSurfaceFormatKHR{VK_FORMAT_B8G8R8A8_UNORM, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR} : formats[0];
  for (auto& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) { chosen = f; break; }
  format_ = chosen.format;

  VkSwapchainKHR old = swapchain_;
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount) ci.minImageCount = std::min(ci.minImageCount, caps.maxImageCount);
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = ext;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = old;
  DYNGI_VK(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &swapchain_));
  if (old) vkDestroySwapchainKHR(ctx_.device(), old, nullptr);
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data());
  extent_ = ext;
  return true;
}

uint32_t Swapchain::acquire() {
  if (!swapchain_) return UINT32_MAX;
  uint32_t index = 0;
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return UINT32_MAX;
  if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) DYNGI_VK(r);
  return index;
}

bool Swapchain::present(uint32_t imageIndex) {
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered_;
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &imageIndex;
  VkResult r = vkQueuePresentKHR(ctx_.queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  DYNGI_VK(r);
  return true;
}

}  // namespace dyngi::render
