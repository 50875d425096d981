#pragma once
// The game's window: GLFW, a Vulkan surface and a FIFO swapchain at the render size. Each frame the
// game's display image (RGBA8, tone-mapped) is blitted into the acquired swapchain image and presented.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <vector>

struct GLFWwindow;

namespace host {

class VulkanHost;

class Window {
 public:
  // The instance extensions a window needs (GLFW's); throws std::runtime_error without a display.
  static std::vector<const char*> instanceExtensions();
  Window(VulkanHost& vk, uint32_t width, uint32_t height, const char* title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  bool open() const;  // false once the user closed it
  void poll();
  // Submits `record` (the frame, then the blit of `display` into the swapchain image) and presents.
  // `display` is RGBA8, in GENERAL, written by compute.
  void present(VkImage display, const std::function<void(VkCommandBuffer)>& record);

 private:
  void createSwapchain();
  void recordBlit(VkCommandBuffer cmd, VkImage display, uint32_t index) const;

  VulkanHost& vk_;
  GLFWwindow* window_ = nullptr;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  uint32_t width_, height_;  // the display image's (the render size)
  VkExtent2D extent_{};      // the swapchain's
  std::vector<VkImage> images_;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  std::vector<VkSemaphore> rendered_;  // one per swapchain image: presentation may still hold the last one
};

}  // namespace host
