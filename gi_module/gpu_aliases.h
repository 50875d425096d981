#pragma once
// Short names the GI module's passes use when declaring push-descriptor bindings.
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/resources.h"

namespace dyngi::gi {

using render::Binding;
using render::Buffer;
using render::DescriptorWrites;
using render::dispatchGroups;
using render::Image;
using render::MemoryUsage;
using render::Pipeline;

constexpr VkShaderStageFlags kCS = VK_SHADER_STAGE_COMPUTE_BIT;
constexpr VkDescriptorType kSSBO = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kUBO = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorageImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

}  // namespace dyngi::gi
