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
  id.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
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

void ShadowPass::drawCasters(VkCommandBuffer cmd, VkImageView target, const glm::mat4& viewProj, const FrameContext& frame,
                             const std::vector<size_t>& draws, bool clear) {
  const uint32_t size = settings_.mapSize;
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = target;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {size, size}};
  ri.layerCount = 1;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.handle());
  setFullViewport(cmd, size, size);
  vkCmdSetDepthBias(cmd, settings_.depthBiasConstant, 0.0f, settings_.depthBiasSlope);
  for (size_t i : draws) {
    glm::mat4 m = viewProj * frame.snapshot.draws[i].model;
    vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(m), &m);
    drawMesh(cmd, *frame.meshes[i]);
  }
  vkCmdEndRendering(cmd);
}

void ShadowPass::execute(FrameContext& frame) {
  ++frameCounter_;
  // Casters, and which of them moved, turned or deformed lately (the first sight of one is no change).
  std::vector<Caster> casters;
  std::vector<size_t> all, statics, moving;
  std::vector<Caster> staticCasters;
  std::unordered_map<scene::Entity, const Caster*> before;
  for (const Caster& c : renderedCasters_) before[c.entity] = &c;
  for (size_t i = 0; i < frame.snapshot.draws.size(); ++i) {
    const DrawItem& d = frame.snapshot.draws[i];
    const GpuMesh* mesh = frame.meshes[i];
    if (!d.castShadows || !mesh || mesh->indexCount == 0) continue;
    Caster c{d.entity, d.mesh, mesh->version, d.model};
    auto it = before.find(d.entity);
    uint64_t& changedAt = casterChangedAt_[d.entity];
    if (rendered_ && (it == before.end() || !(*it->second == c))) changedAt = frameCounter_;
    casters.push_back(c);
    all.push_back(i);
    const bool isMoving = changedAt > 0 && frameCounter_ - changedAt < kSettleFrames;
    (isMoving ? moving : statics).push_back(i);
    if (!isMoving) staticCasters.push_back(c);
  }
  if (casterChangedAt_.size() > 2 * casters.size() + 64) {  // forget casters that are gone
    std::unordered_map<scene::Entity, uint64_t> kept;
    for (const Caster& c : casters) kept[c.entity] = casterChangedAt_[c.entity];
    casterChangedAt_ = std::move(kept);
  }
  // Per layer: kept (nothing it shows changed), redrawn whole (its light view changed, or no caster
  // moves), or rebuilt from the cached static casters plus the moving ones (light still, casters moving).
  const bool castersChanged = !rendered_ || casters != renderedCasters_;
  std::vector<uint32_t> direct, fromCache, cacheRebuild;
  for (uint32_t layer = 0; layer < layerMatrices_.size(); ++layer) {
    const bool viewSame = layer < renderedMatrices_.size() && renderedMatrices_[layer] == layerMatrices_[layer];
    if (rendered_ && viewSame && !castersChanged) continue;
    if (!viewSame || moving.empty()) {
      direct.push_back(layer);
      continue;
    }
    fromCache.push_back(layer);
    if (layer >= cacheMatrices_.size() || cacheMatrices_[layer] != layerMatrices_[layer] || cacheCasters_[layer] != staticCasters)
      cacheRebuild.push_back(layer);
  }
  layersRendered_ = uint32_t(direct.size() + fromCache.size());
  if (rendered_ && layersRendered_ == 0) return;  // the shadow map is current
  rendered_ = true;
  renderedCasters_ = std::move(casters);
  renderedMatrices_ = layerMatrices_;

  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  constexpr VkPipelineStageFlags2 kDepthStages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  constexpr VkAccessFlags2 kDepthAccess = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  if (!cacheRebuild.empty()) {
    const uint32_t layersInUse = uint32_t(layerMatrices_.size());
    if (!staticCache_.valid() || staticCache_.desc().layers < layersInUse) {
      ImageDesc id;
      id.width = id.height = settings_.mapSize;
      id.layers = layersInUse;
      id.format = VK_FORMAT_D32_SFLOAT;
      id.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      id.viewType = layersInUse > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
      id.name = "shadow static cache";
      staticCache_ = Image(ctx_, id);
      cacheMatrices_.clear();
      cacheCasters_.clear();
      cacheRebuild = fromCache;  // the old cache is gone
    }
    cacheMatrices_.resize(layersInUse, glm::mat4(0.0f));
    cacheCasters_.resize(layersInUse);
    staticCache_.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStages, kDepthAccess);
    for (uint32_t layer : cacheRebuild) {
      drawCasters(cmd, staticCache_.layerView(layer), layerMatrices_[layer], frame, statics, true);
      cacheMatrices_[layer] = layerMatrices_[layer];
      cacheCasters_[layer] = staticCasters;
    }
  }
  if (!fromCache.empty()) {
    staticCache_.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    shadowMap_.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    std::vector<VkImageCopy> regions;
    for (uint32_t layer : fromCache) {
      VkImageCopy r{};
      r.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, layer, 1};
      r.dstSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, layer, 1};
      r.extent = {settings_.mapSize, settings_.mapSize, 1};
      regions.push_back(r);
    }
    vkCmdCopyImage(cmd, staticCache_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shadowMap_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   uint32_t(regions.size()), regions.data());
  }
  shadowMap_.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kDepthStages, kDepthAccess);
  for (uint32_t layer : direct) drawCasters(cmd, shadowMap_.layerView(layer), layerMatrices_[layer], frame, all, true);
  for (uint32_t layer : fromCache) drawCasters(cmd, shadowMap_.layerView(layer), layerMatrices_[layer], frame, moving, false);
  shadowMap_.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

}  // namespace dyngi::render
