#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "shared/gpu_types.h"
#include "dyngi/engine/render/light_views.h"
#include "passes.h"
#include "spirv/shadow.vert.spv.h"

namespace dyngi::render {
ShadowPass::ShadowPass(VulkanContext& ctx, const Settings& settings) : ctx_(ctx), settings_(settings) {
  Pipeline::GraphicsDesc d;
  d.vertex = DYNGI_SHADER(spv_shadow_vert);
  d.vertexBindings = {{0, sizeof(GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  d.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  d.depthFormat = VK_FORMAT_D32_SFLOAT;
  d.depthBias = true;
  d.pushConstantBytes = sizeof(glm::mat4);
  d.name = "shadow";
  pipeline_ = Pipeline::graphics(ctx, d);

  lights_ = Buffer(ctx, sizeof(gpu::GpuLight) * DYNGI_MAX_LIGHTS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "lights");
  matrices_ = Buffer(ctx, sizeof(glm::mat4) * settings.maxLayers, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "shadow matrices");
  ImageDesc id;
  id.width = id.height = settings.mapSize;
  id.layers = settings.maxLayers;
  id.format = VK_FORMAT_D32_SFLOAT;
  id.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  id.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  id.name = "shadow map array";
  shadowMap_ = Image(ctx, id);

  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = VK_FILTER_LINEAR;
  sci.minFilter = VK_FILTER_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.compareEnable = VK_TRUE;
  sci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  sci.maxLod = 0.0f;
  DYNGI_VK(vkCreateSampler(ctx.device(), &sci, nullptr, &compareSampler_));
}

ShadowPass::~ShadowPass() { vkDestroySampler(ctx_.device(), compareSampler_, nullptr); }

void ShadowPass::prepare(const RenderSnapshot& snapshot) {
  std::vector<gpu::GpuLight> lights;
  layerMatrices_.clear();
  for (const LightItem& item : snapshot.lights) {
    if (lights.size() >= DYNGI_MAX_LIGHTS) break;
    gpu::GpuLight g = toGpuLight(item);
    const scene::Light& l = item.light;
    uint32_t needed = l.type == scene::LightType::Point ? 6u : 1u;
    bool shadowed = l.castShadows && l.enabled && snapshot.sceneBounds.valid();
    if (shadowed && layerMatrices_.size() + needed > settings_.maxLayers) {
      if (!warnedCapacity_) std::fprintf(stderr, "dyngi: warning: shadow map layers exhausted; further lights are unshadowed\n");
      warnedCapacity_ = true;
      shadowed = false;
    }
    if (shadowed) {
      g.cone.z = float(layerMatrices_.size());
      std::vector<LightView> views = lightViews(item, snapshot.sceneBounds);
      for (const LightView& v : views) layerMatrices_.push_back(v.viewProj);
      // Normal offset of ~1.5 texels: per unit distance for perspective maps, absolute for orthographic.
      g.cone.w = settings_.normalOffsetTexels * views[0].extent / float(settings_.mapSize);
    }
    lights.push_back(g);
  }
  lightCount_ = uint32_t(lights.size());
  if (!lights.empty()) lights_.upload(lights.data(), lights.size() * sizeof(gpu::GpuLight));
  if (!layerMatrices_.empty()) matrices_.upload(layerMatrices_.data(), layerMatrices_.size() * sizeof(glm::mat4));
}

void ShadowPass::execute(FrameContext& frame) {
  std::vector<Caster> casters;
  for (size_t i = 0; i < frame.snapshot.draws.size(); ++i) {
    const DrawItem& d = frame.snapshot.draws[i];
    const GpuMesh* mesh = frame.meshes[i];
    if (d.castShadows && mesh && mesh->indexCount > 0) casters.push_back({d.mesh, mesh->version, d.model});
  }
  // Layers to draw: all when any caster changed, else those whose light view changed.
  const bool castersChanged = !rendered_ || casters != renderedCasters_;
  std::vector<uint32_t> layers;
  for (uint32_t layer = 0; layer < layerMatrices_.size(); ++layer)
    if (castersChanged || layer >= renderedMatrices_.size() || renderedMatrices_[layer] != layerMatrices_[layer]) layers.push_back(layer);
  layersRendered_ = uint32_t(layers.size());
  if (rendered_ && layers.empty()) return;  // the shadow map is current
  rendered_ = true;
  renderedCasters_ = std::move(casters);
  renderedMatrices_ = layerMatrices_;
  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  shadowMap_.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  uint32_t size = settings_.mapSize;
  for (uint32_t layer : layers) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = shadowMap_.layerView(layer);
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {size, size}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.handle());
    VkViewport vp{0, 0, float(size), float(size), 0, 1};
    VkRect2D sc{{0, 0}, {size, size}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
    vkCmdSetDepthBias(cmd, settings_.depthBiasConstant, 0.0f, settings_.depthBiasSlope);
    for (size_t i = 0; i < frame.snapshot.draws.size(); ++i) {
      const DrawItem& d = frame.snapshot.draws[i];
      const GpuMesh* mesh = frame.meshes[i];
      if (!d.castShadows || !mesh || mesh->indexCount == 0) continue;
      glm::mat4 m = layerMatrices_[layer] * d.model;
      vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(m), &m);
      drawMesh(cmd, *mesh);
    }
    vkCmdEndRendering(cmd);
  }
  shadowMap_.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

}  // namespace dyngi::render
