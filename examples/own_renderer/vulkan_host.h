#pragma once
// The game's own Vulkan set-up, written as a host would: its instance and device (dyngi's requirements
// merged in), its buffers and images, one command buffer and fence. Nothing here is dyngi's.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dyngi/engine/render/device_requirements.h"

namespace host {

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceSize size = 0;
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

class VulkanHost {
 public:
  // Throws std::runtime_error (one line) when no device has what the game and dyngi need.
  VulkanHost(const dyngi::render::DeviceRequirements& needs, bool validation);
  ~VulkanHost();
  VulkanHost(const VulkanHost&) = delete;
  VulkanHost& operator=(const VulkanHost&) = delete;

  // The handles dyngi is given.
  dyngi::render::ExternalDevice external() const;

  Buffer buffer(VkDeviceSize size, VkBufferUsageFlags usage);  // host-visible, mapped
  Image image(uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage);
  void destroy(Buffer& b);
  void destroy(Image& i);
  VkShaderModule shader(const uint32_t* code, size_t bytes);
  // Records `record` into the frame's command buffer, submits it, waits for its fence. A window's
  // frame waits for `wait` (the acquired image) before its transfers and signals `signal` (presentable).
  void submit(const std::function<void(VkCommandBuffer)>& record, VkSemaphore wait = VK_NULL_HANDLE,
              VkSemaphore signal = VK_NULL_HANDLE);
  void pushDescriptors(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout, const std::vector<VkWriteDescriptorSet>& writes);

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t validationMessages() const { return messages_; }

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceFeatures enabled_{};
  PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet_ = nullptr;
  uint32_t messages_ = 0;
};

}  // namespace host
