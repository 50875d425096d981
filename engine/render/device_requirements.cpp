#include "dyngi/engine/render/device_requirements.h"

#include <algorithm>
#include <cstring>

namespace dyngi::render {

namespace {

// The core features by name, for `missing` and the merges.
struct FeatureField {
  const char* name;
  VkBool32 VkPhysicalDeviceFeatures::*field;
};
constexpr FeatureField kFeatures[] = {
    {"geometryShader", &VkPhysicalDeviceFeatures::geometryShader},
    {"fragmentStoresAndAtomics", &VkPhysicalDeviceFeatures::fragmentStoresAndAtomics},
    {"shaderStorageImageExtendedFormats", &VkPhysicalDeviceFeatures::shaderStorageImageExtendedFormats},
    {"samplerAnisotropy", &VkPhysicalDeviceFeatures::samplerAnisotropy},
    {"shaderInt64", &VkPhysicalDeviceFeatures::shaderInt64},
};

void addName(std::vector<const char*>& names, const char* name) {
  if (std::none_of(names.begin(), names.end(), [&](const char* n) { return std::strcmp(n, name) == 0; })) names.push_back(name);
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, exts.data());
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

void append(std::string& list, const std::string& what) { list += (list.empty() ? "" : ", ") + what; }

}  // namespace

DeviceRequirements& DeviceRequirements::add(const DeviceRequirements& other) {
  apiVersion = std::max(apiVersion, other.apiVersion);
  for (const char* e : other.instanceExtensions) addName(instanceExtensions, e);
  for (const char* e : other.deviceExtensions) addName(deviceExtensions, e);
  for (const FeatureField& f : kFeatures) features.*f.field = features.*f.field || other.features.*f.field;
  dynamicRendering = dynamicRendering || other.dynamicRendering;
  synchronization2 = synchronization2 || other.synchronization2;
  subgroupBallotInCompute = subgroupBallotInCompute || other.subgroupBallotInCompute;
  return *this;
}

std::string DeviceRequirements::missing(VkPhysicalDevice device) const {
  std::string lacks;
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  if (props.apiVersion < apiVersion)
    append(lacks, "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." + std::to_string(VK_API_VERSION_MINOR(apiVersion)));
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(device, &f2);
  if (dynamicRendering && !f13.dynamicRendering) append(lacks, "dynamicRendering");
  if (synchronization2 && !f13.synchronization2) append(lacks, "synchronization2");
  for (const FeatureField& f : kFeatures)
    if (features.*f.field && !(f2.features.*f.field)) append(lacks, f.name);
  for (const char* e : deviceExtensions)
    if (!hasDeviceExtension(device, e)) append(lacks, e);
  if (subgroupBallotInCompute) {
    VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &sub;
    vkGetPhysicalDeviceProperties2(device, &p2);
    if (!(sub.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT) || !(sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
      append(lacks, "subgroup ballot in compute shaders");
  }
  return lacks;
}

std::string DeviceRequirements::notEnabled(const VkPhysicalDeviceFeatures& enabled) const {
  std::string off;
  for (const FeatureField& f : kFeatures)
    if (features.*f.field && !(enabled.*f.field)) append(off, f.name);
  return off;
}

void DeviceRequirements::mergeInstanceExtensions(std::vector<const char*>& names) const {
  for (const char* e : instanceExtensions) addName(names, e);
}

void DeviceRequirements::mergeDeviceExtensions(std::vector<const char*>& names) const {
  for (const char* e : deviceExtensions) addName(names, e);
}

void DeviceRequirements::mergeFeatures(VkPhysicalDeviceFeatures& into, VkPhysicalDeviceVulkan13Features& into13) const {
  for (const FeatureField& f : kFeatures)
    if (features.*f.field) into.*f.field = VK_TRUE;
  if (dynamicRendering) into13.dynamicRendering = VK_TRUE;
  if (synchronization2) into13.synchronization2 = VK_TRUE;
}

DeviceRequirements rendererRequirements() {
  DeviceRequirements r;
  r.deviceExtensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  return r;
}

}  // namespace dyngi::render
