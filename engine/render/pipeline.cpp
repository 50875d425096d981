#include "dyngi/engine/render/pipeline.h"

#include <utility>

namespace dyngi::render {
namespace {
VkShaderModule makeModule(const VulkanContext& ctx, ShaderCode code) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.bytes;
  ci.pCode = code.words;
  VkShaderModule m;
  DYNGI_VK(vkCreateShaderModule(ctx.device(), &ci, ctx.allocator(), &m));
  return m;
}
}  // namespace

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    setLayout_ = std::exchange(o.setLayout_, VK_NULL_HANDLE);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    bindPoint_ = o.bindPoint_;
  }
  return *this;
}

void Pipeline::reset() {
  if (!ctx_) return;
  VkDevice d = ctx_->device();
  if (pipeline_) vkDestroyPipeline(d, pipeline_, ctx_->allocator());
  if (layout_) vkDestroyPipelineLayout(d, layout_, ctx_->allocator());
  if (setLayout_) vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

void Pipeline::createLayout(std::span<const Binding> bindings, VkShaderStageFlags pcStages, uint32_t pcBytes) {
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (auto& x : bindings) b.push_back({x.binding, x.type, 1, x.stages, nullptr});
  VkDescriptorSetLayoutCreateInfo sci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  sci.bindingCount = uint32_t(b.size());
  sci.pBindings = b.data();
  DYNGI_VK(vkCreateDescriptorSetLayout(ctx_->device(), &sci, ctx_->allocator(), &setLayout_));
  VkPushConstantRange pcr{pcStages, 0, pcBytes};
  VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  lci.setLayoutCount = 1;
  lci.pSetLayouts = &setLayout_;
  lci.pushConstantRangeCount = pcBytes ? 1 : 0;
  lci.pPushConstantRanges = &pcr;
  DYNGI_VK(vkCreatePipelineLayout(ctx_->device(), &lci, ctx_->allocator(), &layout_));
}

LazyPipeline LazyPipeline::compute(VulkanContext& ctx, ShaderCode code, std::span<const Binding> bindings, uint32_t pushConstantBytes,
                                   const char* name, std::span<const uint32_t> specialization) {
  return LazyPipeline([&ctx, code, bindings = std::vector<Binding>(bindings.begin(), bindings.end()), pushConstantBytes, name,
                       spec = std::vector<uint32_t>(specialization.begin(), specialization.end())] {
    return Pipeline::compute(ctx, code, bindings, pushConstantBytes, name, spec);
  });
}

Pipeline Pipeline::compute(VulkanContext& ctx, ShaderCode code, std::span<const Binding> bindings, uint32_t pushConstantBytes,
                           const char* name, std::span<const uint32_t> specialization) {
  Pipeline p;
  p.ctx_ = &ctx;
  p.bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  p.createLayout(bindings, VK_SHADER_STAGE_COMPUTE_BIT, pushConstantBytes);
  VkShaderModule module = makeModule(ctx, code);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, i * 4u, 4u};
  VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), specialization.size_bytes(), specialization.data()};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main",
              specialization.empty() ? nullptr : &spec};
  ci.layout = p.layout_;
  VkResult r = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, ctx.allocator(), &p.pipeline_);
  vkDestroyShaderModule(ctx.device(), module, ctx.allocator());
  DYNGI_VK(r);
  ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline_), name);
  return p;
}

Pipeline Pipeline::graphics(VulkanContext& ctx, const GraphicsDesc& desc) {
  Pipeline p;
  p.ctx_ = &ctx;
  p.bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
  p.createLayout(desc.bindings, desc.pushConstantStages, desc.pushConstantBytes);

  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkShaderModule vs = makeModule(ctx, desc.vertex);
  stages.push_back({VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs, "main", nullptr});
  VkShaderModule gs = VK_NULL_HANDLE;
  if (desc.geometry.words) {
    gs = makeModule(ctx, desc.geometry);
    stages.push_back({VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_GEOMETRY_BIT, gs, "main", nullptr});
  }
  VkShaderModule fs = VK_NULL_HANDLE;
  std::vector<VkSpecializationMapEntry> fragmentEntries(desc.fragmentSpecialization.size());
  for (uint32_t i = 0; i < fragmentEntries.size(); ++i) fragmentEntries[i] = {i, i * 4u, 4u};
  const VkSpecializationInfo fragmentSpec{uint32_t(fragmentEntries.size()), fragmentEntries.data(),
                                          desc.fragmentSpecialization.size() * sizeof(uint32_t), desc.fragmentSpecialization.data()};
  if (desc.fragment.words) {
    fs = makeModule(ctx, desc.fragment);
    stages.push_back({VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main",
                      fragmentEntries.empty() ? nullptr : &fragmentSpec});
  }
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = uint32_t(desc.vertexBindings.size());
  vi.pVertexBindingDescriptions = desc.vertexBindings.data();
  vi.vertexAttributeDescriptionCount = uint32_t(desc.vertexAttributes.size());
  vi.pVertexAttributeDescriptions = desc.vertexAttributes.data();
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = desc.cullMode;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.depthFormat != VK_FORMAT_UNDEFINED;
  ds.depthWriteEnable = ds.depthTestEnable;
  ds.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
  for (auto& b : blends) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blends.size());
  cb.pAttachments = blends.data();
  std::vector<VkDynamicState> dyn = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = uint32_t(dyn.size());
  dy.pDynamicStates = dyn.data();
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &rendering;
  ci.stageCount = uint32_t(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = p.layout_;
  VkResult r = vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, ctx.allocator(), &p.pipeline_);
  vkDestroyShaderModule(ctx.device(), vs, ctx.allocator());
  if (fs) vkDestroyShaderModule(ctx.device(), fs, ctx.allocator());
  if (gs) vkDestroyShaderModule(ctx.device(), gs, ctx.allocator());
  DYNGI_VK(r);
  ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline_), desc.name);
  return p;
}

DescriptorWrites& DescriptorWrites::storageImage(uint32_t binding, VkImageView view) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  e.image = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  entries_.push_back(e);
  return *this;
}
DescriptorWrites& DescriptorWrites::sampledImage(uint32_t binding, VkImageView view, VkSampler sampler, VkImageLayout layout) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
  e.image = {sampler, view, layout};
  entries_.push_back(e);
  return *this;
}
DescriptorWrites& DescriptorWrites::uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize range) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};
  e.buffer = {buffer, 0, range};
  entries_.push_back(e);
  return *this;
}
DescriptorWrites& DescriptorWrites::storageBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize range) {
  Entry e{binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  e.buffer = {buffer, 0, range};
  entries_.push_back(e);
  return *this;
}
void DescriptorWrites::push(const VulkanContext& ctx, VkCommandBuffer cmd, const Pipeline& pipeline) {
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(entries_.size());
  for (auto& e : entries_) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = e.binding;
    w.descriptorCount = 1;
    w.descriptorType = e.type;
    if (e.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || e.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) w.pBufferInfo = &e.buffer;
    else w.pImageInfo = &e.image;
    writes.push_back(w);
  }
  ctx.pushDescriptors(cmd, pipeline.bindPoint(), pipeline.layout(), 0, uint32_t(writes.size()), writes.data());
}

}  // namespace dyngi::render
