#pragma once
// What dyngi needs of a Vulkan instance and device. A host that creates its own merges these into its
// VkInstanceCreateInfo / VkDeviceCreateInfo before it creates them (`merge*`), then hands its handles to
// dyngi (render::ExternalDevice); `missing` names what a physical device lacks, in one line.
#include <string>
#include <vector>

#include "dyngi/engine/render/vk_common.h"

namespace dyngi::render {

struct DeviceRequirements {
  uint32_t apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> instanceExtensions;  // none today
  std::vector<const char*> deviceExtensions;    // VK_KHR_push_descriptor
  VkPhysicalDeviceFeatures features{};          // core features that must be enabled
  bool dynamicRendering = true;                 // Vulkan 1.3 features
  bool synchronization2 = true;
  bool subgroupBallotInCompute = false;         // a property, not a feature: checked by `missing`

  // Every requirement of both (a renderer's and a GI's).
  DeviceRequirements& add(const DeviceRequirements& other);
  // "" when `device` meets every requirement, else what it lacks ("geometryShader, VK_KHR_push_descriptor").
  std::string missing(VkPhysicalDevice device) const;
  // "" when `enabled` (the features a device was created with) holds every required core feature.
  std::string notEnabled(const VkPhysicalDeviceFeatures& enabled) const;
  // Adds the extensions to `names` (no duplicates).
  void mergeInstanceExtensions(std::vector<const char*>& names) const;
  void mergeDeviceExtensions(std::vector<const char*>& names) const;
  // Turns the required features on in a host's feature structs (nothing is turned off).
  void mergeFeatures(VkPhysicalDeviceFeatures& features, VkPhysicalDeviceVulkan13Features& features13) const;
};

// The engine's renderer: Vulkan 1.3 with dynamic rendering and synchronization2, push descriptors.
DeviceRequirements rendererRequirements();

// A device a host made (with the requirements merged in) and keeps: dyngi uses these handles and owns
// none of them. The queue must support graphics and compute; the host synchronizes access to it.
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  const VkAllocationCallbacks* allocator = nullptr;  // passed to every object dyngi creates and destroys
  // The core features the host enabled on `device` (dyngi uses the optional ones it finds here).
  VkPhysicalDeviceFeatures enabledFeatures{};
};

}  // namespace dyngi::render
