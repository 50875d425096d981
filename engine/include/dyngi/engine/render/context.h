#pragma once
// The Vulkan instance, device and queue, plus the few helpers every pass needs. Requires Vulkan 1.3
// (dynamic rendering, synchronization2) and VK_KHR_push_descriptor; prefers a discrete GPU and falls
// back to any device that has a graphics+compute queue (lavapipe on machines without a GPU).
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dyngi/engine/render/device_requirements.h"
#include "dyngi/engine/render/vk_common.h"

namespace dyngi::render {

struct ContextOptions {
  bool validation = false;                       // enable VK_LAYER_KHRONOS_validation when present
  bool requireValidation = false;                // with `validation`: a missing layer is an error, not a warning
  bool synchronizationValidation = false;        // with `validation`: also the layer's hazard checks (slow)
  std::vector<const char*> instanceExtensions;   // e.g. what GLFW needs for a surface
  bool requireSwapchain = false;
  bool quiet = false;                            // do not print the chosen device
};

class VulkanContext {
 public:
  // Its own instance and device.
  explicit VulkanContext(const ContextOptions& options);
  // A host's instance and device (owning none of them): throws VulkanError naming what the device lacks
  // of `needs` (one line). Only its own command pool and fence for one-off work are made here.
  VulkanContext(const ExternalDevice& device, const DeviceRequirements& needs);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkInstance instance() const { return instance_; }
  // The host's allocation callbacks (nullptr: Vulkan's): every vkCreate* / vkDestroy* of dyngi passes it.
  const VkAllocationCallbacks* allocator() const { return allocator_; }
  bool ownsDevice() const { return owned_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return props_; }
  // The core features enabled on the device (each optional one enabled when the device has it).
  const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabledFeatures_; }
  const std::string& deviceName() const { return deviceName_; }
  bool validationEnabled() const { return validationEnabled_; }
  bool timestampsSupported() const { return timestampsSupported_; }
  float timestampPeriodNs() const { return props_.limits.timestampPeriod; }

  // Validation messages of severity error seen so far (tests assert this stays 0).
  uint32_t validationErrorCount() const { return validationErrors_.load(); }
  // Validation errors of every context of this process, including those raised while a context was
  // destroyed (undestroyed objects, leaks): tests check it after their context is gone.
  static uint32_t processValidationErrorCount();
  uint32_t validationWarningCount() const { return validationWarnings_.load(); }

  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred = 0) const;

  // Every device allocation of the engine goes through here. It refuses, before asking the driver, an
  // allocation that would take the heap past its size (DeviceMemoryError naming the object, the request
  // and the heap), and counts live allocations and bytes per heap (a soak run watches them).
  VkDeviceMemory allocateMemory(const VkMemoryRequirements& req, uint32_t memoryType, const char* what);
  void freeMemory(VkDeviceMemory memory, VkDeviceSize bytes, uint32_t memoryType);
  uint64_t liveAllocations() const { return liveAllocations_.load(); }
  VkDeviceSize heapBytesInUse(uint32_t heap) const { return heapUsed_[heap]; }
  VkDeviceSize deviceBytesInUse() const;                      // over every heap
  VkDeviceSize deviceBytesPeak() const { return peakUsed_; }  // the most deviceBytesInUse() has been
  // True when some memory type is both device-local and host-visible (integrated GPUs, lavapipe):
  // uploads can then write directly instead of going through a staging buffer.
  bool hasHostVisibleDeviceLocal() const { return hostVisibleDeviceLocal_; }

  // Records, submits and waits for a one-off command buffer (uploads, readbacks).
  void immediate(const std::function<void(VkCommandBuffer)>& record);

  // Debug-utils labels (no-ops when the extension is absent).
  void beginLabel(VkCommandBuffer cmd, const char* name) const;
  void endLabel(VkCommandBuffer cmd) const;
  void setName(VkObjectType type, uint64_t handle, const char* name) const;

  void pushDescriptors(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                       uint32_t set, uint32_t count, const VkWriteDescriptorSet* writes) const {
    pushDescriptorSet_(cmd, bindPoint, layout, set, count, writes);
  }

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT types,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void create(const ContextOptions& options);
  void adopt(const ExternalDevice& device, const DeviceRequirements& needs);
  void readDeviceProperties();
  void createImmediateResources();
  void createInstance(const ContextOptions& options);
  void pickPhysicalDevice(const ContextOptions& options);
  void createDevice(const ContextOptions& options);
  void destroy();

  VkInstance instance_ = VK_NULL_HANDLE;
  bool owned_ = true;  // false: the host's instance and device
  const VkAllocationCallbacks* allocator_ = nullptr;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool immediatePool_ = VK_NULL_HANDLE;
  VkFence immediateFence_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties props_{};
  VkPhysicalDeviceFeatures enabledFeatures_{};
  VkPhysicalDeviceMemoryProperties memProps_{};
  std::string deviceName_;
  bool validationEnabled_ = false;
  bool debugUtils_ = false;
  bool timestampsSupported_ = false;
  bool hostVisibleDeviceLocal_ = false;
  std::atomic<uint32_t> validationErrors_{0};
  std::atomic<uint64_t> liveAllocations_{0};
  VkDeviceSize heapUsed_[VK_MAX_MEMORY_HEAPS] = {};
  VkDeviceSize peakUsed_ = 0;
  std::atomic<uint32_t> validationWarnings_{0};

  PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet_ = nullptr;
  PFN_vkCmdBeginDebugUtilsLabelEXT beginLabel_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT endLabel_ = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT setName_ = nullptr;
};

}  // namespace dyngi::render
