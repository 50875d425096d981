#pragma once
// Pipelines with one push-descriptor set (set 0) and optional push constants. Push descriptors keep
// passes free of descriptor pools and let a pass bind per-draw textures without descriptor indexing
// (which lavapipe lacks).
#include <functional>
#include <span>
#include <vector>

#include "dyngi/engine/render/context.h"

namespace dyngi::render {

struct Binding {
  uint32_t binding;
  VkDescriptorType type;
  VkShaderStageFlags stages;
};

struct ShaderCode {
  const uint32_t* words;
  size_t bytes;
};
#define DYNGI_SHADER(array) ::dyngi::render::ShaderCode{array, sizeof(array)}

// Workgroups needed to cover n items with `local` items per group.
inline uint32_t dispatchGroups(uint32_t n, uint32_t local) { return (n + local - 1) / local; }

class Pipeline {
 public:
  Pipeline() = default;
  ~Pipeline() { reset(); }
  Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }
  Pipeline& operator=(Pipeline&& o) noexcept;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;
  void reset();

  // `specialization[i]` sets the shader's `layout(constant_id = i) const uint` (a loop bound known when
  // the pipeline is made lets the driver unroll it).
  static Pipeline compute(VulkanContext& ctx, ShaderCode code, std::span<const Binding> bindings, uint32_t pushConstantBytes,
                          const char* name, std::span<const uint32_t> specialization = {});

  struct GraphicsDesc {
    ShaderCode vertex{};
    ShaderCode geometry{};  // optional
    ShaderCode fragment{};  // words == nullptr: depth-only
    // The fragment shader's `layout(constant_id = i)` values (material variants: code a material does
    // not need is left out rather than branched around, which lavapipe would run anyway).
    std::vector<uint32_t> fragmentSpecialization;
    std::vector<VkVertexInputBindingDescription> vertexBindings;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    VkShaderStageFlags pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT;
    uint32_t pushConstantBytes = 0;
    std::vector<Binding> bindings;
    const char* name = nullptr;
  };
  static Pipeline graphics(VulkanContext& ctx, const GraphicsDesc& desc);

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bindPoint() const { return bindPoint_; }

 private:
  void createLayout(std::span<const Binding> bindings, VkShaderStageFlags pcStages, uint32_t pcBytes);

  VulkanContext* ctx_ = nullptr;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
};

// A pipeline made the first time it is asked for: the variants a run never uses (debug views, options
// that are off, materials absent from the scene) cost neither the driver's compile time nor its memory.
// The first use of a variant compiles it there (a hitch of one compile).
class LazyPipeline {
 public:
  LazyPipeline() = default;
  explicit LazyPipeline(std::function<Pipeline()> make) : make_(std::move(make)) {}
  // Pipeline::compute's arguments, kept (the bindings and specialization copied) until first use.
  static LazyPipeline compute(VulkanContext& ctx, ShaderCode code, std::span<const Binding> bindings, uint32_t pushConstantBytes,
                              const char* name, std::span<const uint32_t> specialization = {});
  const Pipeline& get() const {
    if (pipeline_.handle() == VK_NULL_HANDLE && make_) pipeline_ = make_();
    return pipeline_;
  }
  bool made() const { return pipeline_.handle() != VK_NULL_HANDLE; }

 private:
  std::function<Pipeline()> make_;
  mutable Pipeline pipeline_;
};

// Builds push-descriptor writes without boilerplate; the infos live inside the builder.
class DescriptorWrites {
 public:
  DescriptorWrites& storageImage(uint32_t binding, VkImageView view);
  DescriptorWrites& sampledImage(uint32_t binding, VkImageView view, VkSampler sampler,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
  DescriptorWrites& uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWrites& storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize range = VK_WHOLE_SIZE);
  void push(const VulkanContext& ctx, VkCommandBuffer cmd, const Pipeline& pipeline);

 private:
  struct Entry {
    uint32_t binding;
    VkDescriptorType type;
    VkDescriptorImageInfo image{};
    VkDescriptorBufferInfo buffer{};
  };
  std::vector<Entry> entries_;
};

}  // namespace dyngi::render
