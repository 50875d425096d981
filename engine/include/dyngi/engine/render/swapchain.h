#pragma once
// Presentation to a window surface. Recreated on resize; a 0x0 surface (minimised window) is reported
// as not presentable so the caller can skip the frame instead of failing.
#include <vector>

#include "dyngi/engine/render/context.h"

namespace dyngi::render {

class Swapchain {
 public:
  Swapchain(VulkanContext& ctx, VkSurfaceKHR surface);  // takes ownership of the surface
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // (Re)creates for the given framebuffer size. Returns false for a 0x0 size.
  bool recreate(uint32_t width, uint32_t height);
  // Returns the image index, or UINT32_MAX when the swapchain must be recreated.
  uint32_t acquire();
  // Returns false when the swapchain is out of date.
  bool present(uint32_t imageIndex);

  VkImage image(uint32_t i) const { return images_[i]; }
  VkExtent2D extent() const { return extent_; }
  bool valid() const { return swapchain_ != VK_NULL_HANDLE; }
  VkSemaphore acquiredSemaphore() const { return acquired_; }
  VkSemaphore renderedSemaphore() const { return rendered_; }
  VkFormat format() const { return format_; }

 private:
  void destroySwapchain();
  void release();
  VulkanContext& ctx_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  VkExtent2D extent_{0, 0};
  VkFormat format_ = VK_FORMAT_B8G8R8A8_UNORM;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkSemaphore rendered_ = VK_NULL_HANDLE;
};

}  // namespace dyngi::render
