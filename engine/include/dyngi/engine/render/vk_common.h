#pragma once
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace dyngi::render {

struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The device cannot hold what was asked for (a render size or voxel resolution too large for its
// memory heap): a problem with the requested settings rather than a failure, so hosts can report it
// as bad input (the sample exits 2).
struct DeviceMemoryError : VulkanError {
  using VulkanError::VulkanError;
};

const char* vkResultName(VkResult r);

#define DYNGI_VK(expr)                                                                              \
  do {                                                                                              \
    VkResult dyngi_vk_result_ = (expr);                                                             \
    if (dyngi_vk_result_ != VK_SUCCESS)                                                             \
      throw ::dyngi::render::VulkanError(std::string(#expr) + " failed: " +                         \
                                         ::dyngi::render::vkResultName(dyngi_vk_result_));          \
  } while (0)

}  // namespace dyngi::render
