#pragma once
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace dyngi::render {

struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
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
