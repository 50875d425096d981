// own_renderer: a small Vulkan renderer written as a game team would (its own device, glTF loading,
// G-buffer with reversed-Z depth and octahedral normals, direct lighting) that adds dyngi's indirect
// diffuse and specular light to its lighting through dyngi's host API (gi::GiContext). It uses nothing
// of dyngi's renderer, world or importer.
//   own_renderer SCENE.gltf OUT.png [--technique NAME] [--frames N] [--size WxH] [--indirect-out FILE.exr] [--validation] [--window]
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <stb_image_write.h>
#include <tinyexr.h>

#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/gi/gi_context.h"
#include "gbuffer.frag.spv.h"
#include "gbuffer.vert.spv.h"
#include "scene.h"
#include "shade.comp.spv.h"
#include "vulkan_host.h"
#include "window.h"

namespace {

struct Args {
  std::string scene, out, technique = "temporal", indirectOut;
  int frames = 30;
  uint32_t width = 512, height = 512;
  bool validation = false;
  bool window = false;       // a window (GLFW swapchain): runs until closed, or --frames when given
  bool framesGiven = false;
};

bool number(const std::string& s, uint32_t& v) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// An error line, or "" with `a` filled.
std::string parse(int argc, char** argv, Args& a) {
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    const bool hasValue = i + 1 < argc;
    if (s == "--validation") a.validation = true;
    else if (s == "--window") a.window = true;
    else if (s == "--technique" && hasValue) a.technique = argv[++i];
    else if (s == "--indirect-out" && hasValue) a.indirectOut = argv[++i];
    else if (s == "--frames" && hasValue) {
      uint32_t n = 0;
      if (!number(argv[++i], n) || n == 0 || n > 100000) return "--frames wants 1..100000";
      a.frames = int(n);
      a.framesGiven = true;
    } else if (s == "--size" && hasValue) {
      const std::string v = argv[++i];
      const size_t x = v.find('x');
      if (x == std::string::npos || !number(v.substr(0, x), a.width) || !number(v.substr(x + 1), a.height) || a.width == 0 ||
          a.height == 0 || a.width > 8192 || a.height > 8192)
        return "--size wants WxH with 1..8192 each";
    } else if (s.rfind("--", 0) == 0) {
      return "unknown option or missing value: " + s.substr(0, 64);
    } else {
      positional.push_back(s);
    }
  }
  if (positional.size() != 2) return "usage: own_renderer SCENE.gltf OUT.png [--technique NAME] [--frames N] [--size WxH] [--indirect-out FILE.exr] [--validation] [--window]";
  a.scene = positional[0];
  a.out = positional[1];
  return {};
}

// The renderer's GPU side: the G-buffer pass, the shading pass, the images and buffers.
struct Renderer {
  host::VulkanHost& vk;
  uint32_t width, height;
  host::Image depth, normal, baseColor, material, emissive, indirect, specular, hdr, display;
  host::Buffer draws, lights, readback;
  std::vector<host::Buffer> vertices, indices;
  VkPipelineLayout gbufferLayout = VK_NULL_HANDLE, shadeLayout = VK_NULL_HANDLE;
  VkDescriptorSetLayout gbufferSet = VK_NULL_HANDLE, shadeSet = VK_NULL_HANDLE;
  VkPipeline gbuffer = VK_NULL_HANDLE, shade = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;

  Renderer(host::VulkanHost& v, uint32_t w, uint32_t h) : vk(v), width(w), height(h) {}
  ~Renderer() {
    VkDevice d = vk.device();
    for (host::Image* i : {&depth, &normal, &baseColor, &material, &emissive, &indirect, &specular, &hdr, &display}) vk.destroy(*i);
    for (host::Buffer* b : {&draws, &lights, &readback}) vk.destroy(*b);
    for (auto& b : vertices) vk.destroy(b);
    for (auto& b : indices) vk.destroy(b);
    vkDestroyPipeline(d, gbuffer, nullptr);
    vkDestroyPipeline(d, shade, nullptr);
    vkDestroyPipelineLayout(d, gbufferLayout, nullptr);
    vkDestroyPipelineLayout(d, shadeLayout, nullptr);
    vkDestroyDescriptorSetLayout(d, gbufferSet, nullptr);
    vkDestroyDescriptorSetLayout(d, shadeSet, nullptr);
    vkDestroySampler(d, sampler, nullptr);
  }
};

struct GbufferPush {
  glm::mat4 viewProj;
  uint32_t drawIndex;
};
struct ShadePush {
  glm::mat4 invViewProj;
  glm::vec4 cameraPos;
  glm::uvec4 sizeAndLights;
};
struct GpuDraw {
  glm::mat4 model;
  glm::vec4 baseColor, emissiveRoughness;
};
struct GpuLight {
  glm::vec4 positionType, directionRange, radiance, cones;
};

VkDescriptorSetLayout setLayout(VkDevice d, const std::vector<VkDescriptorSetLayoutBinding>& bindings) {
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  ci.bindingCount = uint32_t(bindings.size());
  ci.pBindings = bindings.data();
  VkDescriptorSetLayout l;
  vkCreateDescriptorSetLayout(d, &ci, nullptr, &l);
  return l;
}

VkPipelineLayout pipelineLayout(VkDevice d, VkDescriptorSetLayout set, VkShaderStageFlags stages, uint32_t pushBytes) {
  VkPushConstantRange range{stages, 0, pushBytes};
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = 1;
  ci.pSetLayouts = &set;
  ci.pushConstantRangeCount = 1;
  ci.pPushConstantRanges = &range;
  VkPipelineLayout l;
  vkCreatePipelineLayout(d, &ci, nullptr, &l);
  return l;
}

constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16_SFLOAT, kColorFormat = VK_FORMAT_R8G8B8A8_UNORM, kHalfFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

void createGbufferPipeline(Renderer& r) {
  VkDevice d = r.vk.device();
  const VkShaderStageFlags vf = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  r.gbufferSet = setLayout(d, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, vf, nullptr}});
  r.gbufferLayout = pipelineLayout(d, r.gbufferSet, vf, sizeof(GbufferPush));
  VkShaderModule vs = r.vk.shader(gbuffer_vert, sizeof(gbuffer_vert)), fs = r.vk.shader(gbuffer_frag, sizeof(gbuffer_frag));
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs, "main", nullptr},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main", nullptr}};
  VkVertexInputBindingDescription binding{0, 24, VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attributes[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}, {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12}};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = 1;
  vi.pVertexBindingDescriptions = &binding;
  vi.vertexAttributeDescriptionCount = 2;
  vi.pVertexAttributeDescriptions = attributes;
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(r.width), float(r.height), 0, 1};
  VkRect2D scissor{{0, 0}, {r.width, r.height}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed Z: near is 1
  VkPipelineColorBlendAttachmentState blend[4]{};
  for (auto& b : blend) b.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 4;
  cb.pAttachments = blend;
  const VkFormat formats[4] = {kNormalFormat, kColorFormat, kColorFormat, kHalfFormat};
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 4;
  rendering.pColorAttachmentFormats = formats;
  rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &rendering;
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.layout = r.gbufferLayout;
  vkCreateGraphicsPipelines(d, VK_NULL_HANDLE, 1, &ci, nullptr, &r.gbuffer);
  vkDestroyShaderModule(d, vs, nullptr);
  vkDestroyShaderModule(d, fs, nullptr);
}

void createShadePipeline(Renderer& r) {
  VkDevice d = r.vk.device();
  const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (uint32_t i = 0; i < 5; ++i) b.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr});
  b.push_back({5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr});
  b.push_back({6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr});
  b.push_back({7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr});
  b.push_back({8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr});
  b.push_back({9, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr});
  r.shadeSet = setLayout(d, b);
  r.shadeLayout = pipelineLayout(d, r.shadeSet, cs, sizeof(ShadePush));
  VkShaderModule m = r.vk.shader(shade_comp, sizeof(shade_comp));
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = VkPipelineShaderStageCreateInfo{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, m, "main", nullptr};
  ci.layout = r.shadeLayout;
  vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &ci, nullptr, &r.shade);
  vkDestroyShaderModule(d, m, nullptr);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  vkCreateSampler(d, &si, nullptr, &r.sampler);
}

void createTargets(Renderer& r) {
  const VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  r.depth = r.vk.image(r.width, r.height, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  r.normal = r.vk.image(r.width, r.height, kNormalFormat, attachment);
  r.baseColor = r.vk.image(r.width, r.height, kColorFormat, attachment);
  r.material = r.vk.image(r.width, r.height, kColorFormat, attachment);
  r.emissive = r.vk.image(r.width, r.height, kHalfFormat, attachment);
  r.indirect = r.vk.image(r.width, r.height, VK_FORMAT_R32G32B32A32_SFLOAT, storage);
  r.specular = r.vk.image(r.width, r.height, VK_FORMAT_R32G32B32A32_SFLOAT, storage);
  r.hdr = r.vk.image(r.width, r.height, VK_FORMAT_R32G32B32A32_SFLOAT, storage);
  r.display = r.vk.image(r.width, r.height, VK_FORMAT_R8G8B8A8_UNORM, storage);  // the window's
  r.readback = r.vk.buffer(VkDeviceSize(r.width) * r.height * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
}

void writeLight(Renderer& r, size_t i, const host::Light& l) {
  static_cast<GpuLight*>(r.lights.mapped)[i] = {glm::vec4(l.position, float(l.type)), glm::vec4(l.direction, l.range),
                                                glm::vec4(l.color * l.intensity, 0.0f),
                                                glm::vec4(std::cos(l.innerCone), std::cos(l.outerCone), 0.0f, 0.0f)};
}

dyngi::gi::LightDesc lightDesc(const host::Light& l) {
  dyngi::gi::LightDesc d;
  d.type = l.type == 0 ? dyngi::gi::LightDesc::Type::Directional : l.type == 2 ? dyngi::gi::LightDesc::Type::Spot : dyngi::gi::LightDesc::Type::Point;
  d.color = l.color;
  d.intensity = l.intensity;
  d.position = l.position;
  d.direction = l.direction;
  d.range = l.range;
  d.innerConeAngle = l.innerCone;
  d.outerConeAngle = l.outerCone;
  return d;
}

void writeVertices(Renderer& r, uint32_t mesh, const host::Mesh& m) {
  auto* out = static_cast<float*>(r.vertices[mesh].mapped);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    std::memcpy(out + 6 * i, &m.positions[i], 12);
    std::memcpy(out + 6 * i + 3, &m.normals[i], 12);
  }
}

// dyngi's handles of the game's meshes, instances and lights, in the scene's order.
struct GiHandles {
  std::vector<dyngi::gi::MeshHandle> meshes;
  std::vector<dyngi::gi::InstanceHandle> instances;
  std::vector<dyngi::gi::LightHandle> lights;
};

// The scene on both sides: the game's vertex buffers and draw list, and dyngi's copy through its calls.
GiHandles uploadScene(Renderer& r, const host::Scene& scene, dyngi::gi::GiContext& gi) {
  GiHandles handles;
  std::vector<dyngi::gi::MeshHandle>& meshes = handles.meshes;
  for (const host::Mesh& m : scene.meshes) {
    r.vertices.push_back(r.vk.buffer(m.positions.size() * 24, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
    writeVertices(r, uint32_t(r.vertices.size() - 1), m);
    host::Buffer ib = r.vk.buffer(m.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    std::memcpy(ib.mapped, m.indices.data(), m.indices.size() * 4);
    r.indices.push_back(ib);
    meshes.push_back(gi.addMesh({m.positions, m.normals, {}, m.indices, {}}));
  }
  std::vector<dyngi::gi::MaterialHandle> materials;
  for (const host::Material& m : scene.materials) {
    dyngi::gi::MaterialDesc d;
    d.baseColor = m.baseColor;
    d.emissive = m.emissive;
    d.metallic = m.metallic;
    d.roughness = m.roughness;
    materials.push_back(gi.addMaterial(d));
  }
  r.draws = r.vk.buffer(std::max<size_t>(scene.instances.size(), 1) * sizeof(GpuDraw), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const host::Instance& inst = scene.instances[i];
    const host::Material& m = scene.materials[inst.material];
    static_cast<GpuDraw*>(r.draws.mapped)[i] = {inst.transform, glm::vec4(glm::vec3(m.baseColor), m.metallic), glm::vec4(m.emissive, m.roughness)};
    handles.instances.push_back(gi.addInstance({meshes[inst.mesh], materials[inst.material], inst.transform, inst.dynamic}));
  }
  r.lights = r.vk.buffer(std::max<size_t>(scene.lights.size(), 1) * sizeof(GpuLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    writeLight(r, i, scene.lights[i]);
    handles.lights.push_back(gi.addLight(lightDesc(scene.lights[i])));
  }
  return handles;
}

// The clip at `seconds` on both sides: the game's draws and skinned vertex buffers (the last frame has
// finished with them: the game waits for each frame), and the same changes told to dyngi.
void animateScene(Renderer& r, host::Scene& scene, const GiHandles& handles, dyngi::gi::GiContext& gi, float seconds) {
  for (size_t i : host::animate(scene, seconds)) {
    const host::Instance& inst = scene.instances[i];
    glm::mat4& drawn = static_cast<GpuDraw*>(r.draws.mapped)[i].model;
    if (drawn != inst.transform) {
      drawn = inst.transform;
      gi.setTransform(handles.instances[i], inst.transform);
    }
    if (inst.skin >= 0) {
      const host::Mesh& m = scene.meshes[inst.mesh];
      writeVertices(r, inst.mesh, m);
      gi.updateMesh(handles.meshes[inst.mesh], m.positions, m.normals);
    }
  }
}

// The light at `seconds` of the window's motion: a spot or directional light's direction circles its
// own, a point light circles its place by a quarter of its distance to the camera.
host::Light sweep(host::Light l, double seconds, const glm::vec3& eye) {
  const float a = float(seconds) * 0.8f;
  const glm::vec3 circle(std::cos(a), 0.0f, std::sin(a));
  if (l.type == 1) l.position += 0.25f * glm::length(eye - l.position) * circle;
  else l.direction = glm::normalize(l.direction + 0.35f * circle);
  return l;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
constexpr VkAccessFlags2 kAnyAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

void recordGbuffer(Renderer& r, VkCommandBuffer cmd, const host::Scene& scene, const glm::mat4& viewProj) {
  for (host::Image* i : {&r.normal, &r.baseColor, &r.material, &r.emissive})
    imageBarrier(cmd, i->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kAll, kAnyAccess,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  imageBarrier(cmd, r.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kAll, kAnyAccess,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  VkRenderingAttachmentInfo colors[4]{};
  host::Image* targets[4] = {&r.normal, &r.baseColor, &r.material, &r.emissive};
  for (int i = 0; i < 4; ++i) {
    colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colors[i].imageView = targets[i]->view;
    colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = r.depth.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z: the far plane
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {r.width, r.height}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 4;
  ri.pColorAttachments = colors;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.gbuffer);
  VkDescriptorBufferInfo drawsInfo{r.draws.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstBinding = 0;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w.pBufferInfo = &drawsInfo;
  r.vk.pushDescriptors(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.gbufferLayout, {w});
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const uint32_t mesh = scene.instances[i].mesh;
    const GbufferPush pc{viewProj, uint32_t(i)};
    vkCmdPushConstants(cmd, r.gbufferLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &r.vertices[mesh].buffer, &offset);
    vkCmdBindIndexBuffer(cmd, r.indices[mesh].buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, uint32_t(scene.meshes[mesh].indices.size()), 1, 0, 0, 0);
  }
  vkCmdEndRendering(cmd);
  for (host::Image* i : targets)
    imageBarrier(cmd, i->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  imageBarrier(cmd, r.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
               VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void recordShade(Renderer& r, VkCommandBuffer cmd, const glm::mat4& invViewProj, const glm::vec3& eye, uint32_t lightCount) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.shade);
  std::vector<VkDescriptorImageInfo> images = {
      {r.sampler, r.depth.view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}, {r.sampler, r.normal.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {r.sampler, r.baseColor.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},   {r.sampler, r.material.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {r.sampler, r.emissive.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},    {VK_NULL_HANDLE, r.indirect.view, VK_IMAGE_LAYOUT_GENERAL},
      {VK_NULL_HANDLE, r.specular.view, VK_IMAGE_LAYOUT_GENERAL},                {VK_NULL_HANDLE, r.hdr.view, VK_IMAGE_LAYOUT_GENERAL},
      {VK_NULL_HANDLE, r.display.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkDescriptorBufferInfo lightsInfo{r.lights.buffer, 0, VK_WHOLE_SIZE};
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0; i < 10; ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = i;
    w.descriptorCount = 1;
    if (i == 7) {
      w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      w.pBufferInfo = &lightsInfo;
    } else {
      w.descriptorType = i < 5 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      w.pImageInfo = &images[i < 7 ? i : i - 1];
    }
    writes.push_back(w);
  }
  r.vk.pushDescriptors(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.shadeLayout, writes);
  const ShadePush pc{invViewProj, glm::vec4(eye, 1.0f), glm::uvec4(r.width, r.height, lightCount, 0)};
  vkCmdPushConstants(cmd, r.shadeLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, (r.width + 7) / 8, (r.height + 7) / 8, 1);
}

// An RGBA32F image's pixels, through the readback buffer.
std::vector<float> readImage(Renderer& r, host::Image& image, VkImageLayout layout) {
  r.vk.submit([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kAll, kAnyAccess, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {r.width, r.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.readback.buffer, 1, &region);
    imageBarrier(cmd, image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT, kAll, kAnyAccess);
  });
  std::vector<float> pixels(size_t(r.width) * r.height * 4);
  std::memcpy(pixels.data(), r.readback.mapped, pixels.size() * 4);
  return pixels;
}

// The HDR image tone-mapped (ACES fit) and sRGB-encoded to a PNG.
bool writePng(const std::string& path, const std::vector<float>& hdr, uint32_t w, uint32_t h) {
  std::vector<uint8_t> bytes(size_t(w) * h * 3);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = std::max(hdr[4 * i + size_t(c)], 0.0f);
      const float mapped = std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
      const float srgb = mapped <= 0.0031308f ? 12.92f * mapped : 1.055f * std::pow(mapped, 1.0f / 2.4f) - 0.055f;
      bytes[3 * i + size_t(c)] = uint8_t(std::lround(srgb * 255.0f));
    }
  return stbi_write_png(path.c_str(), int(w), int(h), 3, bytes.data(), int(w) * 3) != 0;
}

bool writeExr(const std::string& path, const std::vector<float>& rgba, uint32_t w, uint32_t h) {
  const char* err = nullptr;
  const int r = SaveEXR(rgba.data(), int(w), int(h), 4, 0, path.c_str(), &err);
  if (err) FreeEXRErrorMessage(err);
  return r == TINYEXR_SUCCESS;
}

// What the GI is told of the game's frame: its camera, its G-buffer's views and encoding, and the
// game's own images for the indirect diffuse and specular light.
dyngi::gi::FrameDesc describeFrame(const Renderer& r, const glm::mat4& view, const glm::mat4& proj) {
  dyngi::gi::FrameDesc f;
  f.width = r.width;
  f.height = r.height;
  f.camera = {view, proj};
  f.gbuffer.depth = r.depth.view;
  f.gbuffer.reversedZ = true;
  f.gbuffer.normal = r.normal.view;
  f.gbuffer.normalEncoding = dyngi::gi::GBufferDesc::NormalEncoding::WorldOctahedral;
  f.gbuffer.baseColor = r.baseColor.view;
  f.gbuffer.roughness = r.material.view;
  f.gbuffer.roughnessChannel = 0;
  f.gbuffer.metallic = r.material.view;
  f.gbuffer.metallicChannel = 1;
  f.gbuffer.emissive = r.emissive.view;
  f.outputs = {r.indirect.view, VK_FORMAT_R32G32B32A32_SFLOAT, r.specular.view, VK_FORMAT_R32G32B32A32_SFLOAT};
  return f;
}

// The PNG, and the GI's indirect light as EXR when asked: 0, or 1 when a file cannot be written.
int writeOutputs(Renderer& r, const Args& a) {
  int status = 0;
  const std::vector<float> hdr = readImage(r, r.hdr, VK_IMAGE_LAYOUT_GENERAL);
  if (!writePng(a.out, hdr, a.width, a.height)) {
    std::fprintf(stderr, "own_renderer: %s: cannot write\n", a.out.c_str());
    status = 1;
  }
  if (!a.indirectOut.empty()) {
    std::vector<float> indirect = readImage(r, r.indirect, VK_IMAGE_LAYOUT_GENERAL);
    for (size_t i = 3; i < indirect.size(); i += 4) indirect[i] = 1.0f;  // the indirect view's alpha
    if (!writeExr(a.indirectOut, indirect, a.width, a.height)) {
      std::fprintf(stderr, "own_renderer: %s: cannot write\n", a.indirectOut.c_str());
      status = 1;
    }
  }
  return status;
}

int run(const Args& a) {
  host::Scene scene;
  if (std::string error = host::loadScene(a.scene, scene); !error.empty()) {
    std::fprintf(stderr, "own_renderer: %s\n", error.c_str());
    return 2;
  }
  // The game's own needs merged with dyngi's: a window's surface and swapchain.
  dyngi::render::DeviceRequirements needs = dyngi::gi::GiContext::requirements();
  if (a.window) {
    dyngi::render::DeviceRequirements windowNeeds;
    windowNeeds.instanceExtensions = host::Window::instanceExtensions();
    windowNeeds.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    needs.add(windowNeeds);
  }
  host::VulkanHost vk(needs, a.validation);
  int status = 0;
  {
    dyngi::gi::GiSettings settings;
    settings.technique = a.technique;
    dyngi::gi::GiContext gi(vk.external(), settings);
    Renderer r(vk, a.width, a.height);
    createTargets(r);
    createGbufferPipeline(r);
    createShadePipeline(r);
    const GiHandles handles = uploadScene(r, scene, gi);
    std::optional<host::Window> window;
    if (a.window) window.emplace(vk, a.width, a.height, "own_renderer (dyngi GI)");
    // The game's camera: reversed Z (near at depth 1), Vulkan's y down.
    const glm::mat4 view = glm::inverse(scene.camera.world);
    glm::mat4 proj = glm::perspectiveRH_ZO(scene.camera.yfov, float(a.width) / float(a.height), scene.camera.zfar, scene.camera.znear);
    proj[1][1] *= -1.0f;
    const glm::mat4 viewProj = proj * view;
    dyngi::gi::FrameDesc f = describeFrame(r, view, proj);
    auto recordFrame = [&](VkCommandBuffer cmd) {
      recordGbuffer(r, cmd, scene, viewProj);
      for (host::Image* out : {&r.indirect, &r.specular, &r.hdr, &r.display})
        imageBarrier(cmd, out->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, kAll, kAnyAccess,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      gi.recordFrame(cmd, f);
      recordShade(r, cmd, glm::inverse(viewProj), glm::vec3(scene.camera.world[3]), uint32_t(scene.lights.size()));
    };
    int frames = 0;
    float clipTime = 0.0f;
    for (; window ? window->open() && (!a.framesGiven || frames < a.frames) : frames < a.frames; ++frames) {
      f.time = double(frames) / 60.0;
      // The clip's clock advances a 60th of a second a frame before the frame is drawn (dyngi's sample
      // plays a clip the same way), wrapped at the clip's end.
      if (!scene.animation.empty()) {
        clipTime = std::fmod(clipTime + 1.0f / 60.0f, scene.animationDuration);
        animateScene(r, scene, handles, gi, clipTime);
      }
      if (window) {
        window->poll();
        if (!scene.lights.empty()) {  // in the window the first light sweeps, so the bounce light is seen to follow
          const host::Light moved = sweep(scene.lights[0], f.time, glm::vec3(scene.camera.world[3]));
          writeLight(r, 0, moved);
          gi.updateLight(handles.lights[0], lightDesc(moved));
        }
        window->present(r.display.image, recordFrame);
      } else {
        vk.submit(recordFrame);
      }
    }
    status = writeOutputs(r, a);
    std::printf("own_renderer: %s, %d frames of --gi %s at %ux%u: wrote %s\n", a.scene.c_str(), frames, a.technique.c_str(), a.width, a.height,
                a.out.c_str());
  }
  if (vk.validationMessages() > 0) {
    std::fprintf(stderr, "own_renderer: %u validation message(s)\n", vk.validationMessages());
    status = 1;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string error = parse(argc, argv, a); !error.empty()) {
    std::fprintf(stderr, "own_renderer: %s\n", error.c_str());
    return 2;
  }
  try {
    return run(a);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "own_renderer: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_renderer: %s\n", e.what());
    return 1;
  }
}
