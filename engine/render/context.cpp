#include "dyngi/engine/render/context.h"

#include <algorithm>

#include <cstdio>
#include <cstring>

namespace dyngi::render {

const char* vkResultName(VkResult r) {
  switch (r) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_SUBOPTIMAL_KHR: return "VK_SUBOPTIMAL_KHR";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_OUT_OF_DATE_KHR: return "VK_ERROR_OUT_OF_DATE_KHR";
    case VK_ERROR_SURFACE_LOST_KHR: return "VK_ERROR_SURFACE_LOST_KHR";
    default: return "VkResult(other)";
  }
}

namespace {
std::atomic<uint32_t> gProcessValidationErrors{0};
}

uint32_t VulkanContext::processValidationErrorCount() { return gProcessValidationErrors.load(); }

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* self = static_cast<VulkanContext*>(user);
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++self->validationErrors_;
    ++gProcessValidationErrors;
    std::fprintf(stderr, "vulkan validation error: %s\n", data->pMessage);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ++self->validationWarnings_;
    std::fprintf(stderr, "vulkan validation warning: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

namespace {
bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}
bool hasInstanceExtension(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}
bool deviceHasExtension(VkPhysicalDevice dev, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(dev, nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}
}  // namespace

VulkanContext::VulkanContext(const ContextOptions& options) {
  // A destructor does not run for a constructor that throws: release what was made, then rethrow.
  try {
    create(options);
  } catch (...) {
    destroy();
    throw;
  }
}

VulkanContext::VulkanContext(const ExternalDevice& device, const DeviceRequirements& needs) {
  try {
    adopt(device, needs);
  } catch (...) {
    destroy();
    throw;
  }
}

void VulkanContext::create(const ContextOptions& options) {
  createInstance(options);
  pickPhysicalDevice(options);
  createDevice(options);
  createImmediateResources();
}

void VulkanContext::adopt(const ExternalDevice& d, const DeviceRequirements& needs) {
  owned_ = false;
  if (!d.instance || !d.physicalDevice || !d.device || !d.queue) throw VulkanError("the host's device: a null instance, physical device, device or queue");
  instance_ = d.instance;
  physical_ = d.physicalDevice;
  device_ = d.device;
  queue_ = d.queue;
  queueFamily_ = d.queueFamily;
  allocator_ = d.allocator;
  enabledFeatures_ = d.enabledFeatures;
  if (std::string lacks = needs.missing(physical_); !lacks.empty()) throw VulkanError("the host's Vulkan device lacks what dyngi needs: " + lacks);
  if (std::string off = needs.notEnabled(enabledFeatures_); !off.empty())
    throw VulkanError("the host's Vulkan device was created without " + off + " (merge dyngi's DeviceRequirements into its features)");
  readDeviceProperties();
  pushDescriptorSet_ = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!pushDescriptorSet_) throw VulkanError("the host's Vulkan device was created without VK_KHR_push_descriptor (merge dyngi's DeviceRequirements)");
  createImmediateResources();
}

// Properties, memory types and queue timestamps of physical_.
void VulkanContext::readDeviceProperties() {
  vkGetPhysicalDeviceProperties(physical_, &props_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memProps_);
  deviceName_ = props_.deviceName;
  for (uint32_t i = 0; i < memProps_.memoryTypeCount; ++i) {
    auto fl = memProps_.memoryTypes[i].propertyFlags;
    if ((fl & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) && (fl & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)) hostVisibleDeviceLocal_ = true;
  }
  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qf(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, qf.data());
  timestampsSupported_ = queueFamily_ < qn && qf[queueFamily_].timestampValidBits > 0 && props_.limits.timestampComputeAndGraphics;
}

void VulkanContext::createImmediateResources() {
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queueFamily_;
  DYNGI_VK(vkCreateCommandPool(device_, &pci, allocator_, &immediatePool_));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  DYNGI_VK(vkCreateFence(device_, &fci, allocator_, &immediateFence_));
}

// The instance with the validation layer (and its synchronization checks) when asked for, and the
// debug-utils functions: messenger, labels, object names.
void VulkanContext::createInstance(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "dyngi";
  app.pEngineName = "dyngi";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> exts = options.instanceExtensions;
  debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils_) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  std::vector<const char*> layers;
  if (options.validation) {
    if (hasLayer("VK_LAYER_KHRONOS_validation")) {
      layers.push_back("VK_LAYER_KHRONOS_validation");
      validationEnabled_ = true;
    } else if (options.requireValidation) {
      throw VulkanError("validation is required but VK_LAYER_KHRONOS_validation is not installed (Debian: vulkan-validationlayers)");
    } else {
      std::fprintf(stderr, "dyngi: warning: validation requested but VK_LAYER_KHRONOS_validation is not installed\n");
    }
  }
  VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = &VulkanContext::debugCallback;
  dbg.pUserData = this;

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledExtensionCount = uint32_t(exts.size());
  ici.ppEnabledExtensionNames = exts.data();
  ici.enabledLayerCount = uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  if (validationEnabled_ && debugUtils_) ici.pNext = &dbg;
  if (validationEnabled_ && options.synchronizationValidation) {
    features.pNext = ici.pNext;
    ici.pNext = &features;
  }
  DYNGI_VK(vkCreateInstance(&ici, nullptr, &instance_));

  if (debugUtils_) {
    if (validationEnabled_) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (create) DYNGI_VK(create(instance_, &dbg, nullptr, &messenger_));
    }
    beginLabel_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    endLabel_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
    setName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
  }
}

// A device: discrete > integrated > anything, among those that meet our requirements; the error names
// what each device lacks.
void VulkanContext::pickPhysicalDevice(const ContextOptions& options) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  int bestScore = -1;
  std::string rejected;
  for (VkPhysicalDevice dev : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(dev, &p);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f13;
    vkGetPhysicalDeviceFeatures2(dev, &f2);
    std::string why;
    if (p.apiVersion < VK_API_VERSION_1_3) why = "Vulkan 1.3 not supported";
    else if (!f13.dynamicRendering || !f13.synchronization2) why = "no dynamic rendering / synchronization2";
    else if (!deviceHasExtension(dev, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) why = "no VK_KHR_push_descriptor";
    else if (options.requireSwapchain && !deviceHasExtension(dev, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) why = "no swapchain";
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(dev, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qf(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(dev, &qn, qf.data());
    int family = -1;
    for (uint32_t i = 0; i < qn; ++i)
      if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) { family = int(i); break; }
    if (family < 0 && why.empty()) why = "no graphics+compute queue";
    if (!why.empty()) {
      rejected += std::string(" ") + p.deviceName + " (" + why + ");";
      continue;
    }
    int score = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ? 3 : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2 : 1;
    if (score > bestScore) {
      bestScore = score;
      physical_ = dev;
      queueFamily_ = uint32_t(family);
      timestampsSupported_ = qf[size_t(family)].timestampValidBits > 0 && p.limits.timestampComputeAndGraphics;
    }
  }
  if (!physical_) throw VulkanError("no usable Vulkan device:" + (rejected.empty() ? std::string(" none found") : rejected));
  readDeviceProperties();
  if (!options.quiet) std::fprintf(stderr, "dyngi: Vulkan device: %s\n", deviceName_.c_str());
}

// The logical device with the features and extensions the renderer and the GI use, its queue.
void VulkanContext::createDevice(const ContextOptions& options) {
  VkPhysicalDeviceFeatures supported;
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f12;
  // Optional features later stages use (voxelization; rg32ui storage images in the indirect gather),
  // enabled when present.
  f2.features.geometryShader = supported.geometryShader;
  f2.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
  f2.features.shaderInt64 = supported.shaderInt64;
  f2.features.samplerAnisotropy = supported.samplerAnisotropy;
  f2.features.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;

  std::vector<const char*> devExts = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  if (options.requireSwapchain) devExts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &f2;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(devExts.size());
  dci.ppEnabledExtensionNames = devExts.data();
  DYNGI_VK(vkCreateDevice(physical_, &dci, nullptr, &device_));
  enabledFeatures_ = f2.features;
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  pushDescriptorSet_ = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!pushDescriptorSet_) throw VulkanError("vkCmdPushDescriptorSetKHR not found");
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() {
  if (device_) {
    // The host's device: only the queue this context submitted to is waited for, at teardown.
    if (owned_) vkDeviceWaitIdle(device_);
    else if (queue_) vkQueueWaitIdle(queue_);
    if (immediateFence_) vkDestroyFence(device_, immediateFence_, allocator_);
    if (immediatePool_) vkDestroyCommandPool(device_, immediatePool_, allocator_);
    immediateFence_ = VK_NULL_HANDLE;
    immediatePool_ = VK_NULL_HANDLE;
    if (owned_) vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (!owned_) {
    instance_ = VK_NULL_HANDLE;
    return;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  messenger_ = VK_NULL_HANDLE;
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

VkDeviceMemory VulkanContext::allocateMemory(const VkMemoryRequirements& req, uint32_t memoryType, const char* what) {
  const uint32_t heap = memProps_.memoryTypes[memoryType].heapIndex;
  const VkDeviceSize heapSize = memProps_.memoryHeaps[heap].size;
  constexpr double MiB = 1024.0 * 1024.0;
  if (req.size > heapSize || heapUsed_[heap] > heapSize - req.size) {
    char msg[320];
    std::snprintf(msg, sizeof msg,
                  "device memory: '%s' needs %.0f MiB, but %.0f MiB of the device's %.0f MiB heap are in use "
                  "(try a smaller render size or voxel resolution)",
                  what ? what : "allocation", double(req.size) / MiB, double(heapUsed_[heap]) / MiB, double(heapSize) / MiB);
    throw DeviceMemoryError(msg);
  }
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = memoryType;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult r = vkAllocateMemory(device_, &mai, allocator_, &memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY) {
    char msg[320];
    std::snprintf(msg, sizeof msg, "device memory: the driver refused '%s' (%.0f MiB) with %s (try a smaller render size or voxel resolution)",
                  what ? what : "allocation", double(req.size) / MiB, vkResultName(r));
    throw DeviceMemoryError(msg);
  }
  DYNGI_VK(r);
  heapUsed_[heap] += req.size;
  ++liveAllocations_;
  peakUsed_ = std::max(peakUsed_, deviceBytesInUse());
  return memory;
}

VkDeviceSize VulkanContext::deviceBytesInUse() const {
  VkDeviceSize total = 0;
  for (VkDeviceSize used : heapUsed_) total += used;
  return total;
}

void VulkanContext::freeMemory(VkDeviceMemory memory, VkDeviceSize bytes, uint32_t memoryType) {
  if (!memory) return;
  vkFreeMemory(device_, memory, allocator_);
  heapUsed_[memProps_.memoryTypes[memoryType].heapIndex] -= bytes;
  --liveAllocations_;
}

uint32_t VulkanContext::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
    for (uint32_t i = 0; i < memProps_.memoryTypeCount; ++i)
      if ((typeBits & (1u << i)) && (memProps_.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  throw VulkanError("no suitable Vulkan memory type");
}

void VulkanContext::immediate(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = immediatePool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  DYNGI_VK(vkAllocateCommandBuffers(device_, &ai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  DYNGI_VK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  DYNGI_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  DYNGI_VK(vkResetFences(device_, 1, &immediateFence_));
  DYNGI_VK(vkQueueSubmit(queue_, 1, &si, immediateFence_));
  DYNGI_VK(vkWaitForFences(device_, 1, &immediateFence_, VK_TRUE, UINT64_MAX));
  vkFreeCommandBuffers(device_, immediatePool_, 1, &cmd);
}

void VulkanContext::beginLabel(VkCommandBuffer cmd, const char* name) const {
  if (!beginLabel_) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name;
  beginLabel_(cmd, &label);
}
void VulkanContext::endLabel(VkCommandBuffer cmd) const {
  if (endLabel_) endLabel_(cmd);
}
void VulkanContext::setName(VkObjectType type, uint64_t handle, const char* name) const {
  if (!setName_ || !name) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  setName_(device_, &info);
}

}  // namespace dyngi::render
