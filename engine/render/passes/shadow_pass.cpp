#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/engine/render/draw_pass.h"
#include "shared/gpu_types.h"
#include "dyngi/engine/render/light_views.h"
#include "passes.h"
#include "spirv/shadow.frag.spv.h"
#include "spirv/shadow.vert.spv.h"
#include "spirv/shadow_masked.frag.spv.h"
#include "spirv/shadow_masked.vert.spv.h"

namespace dyngi::render {
namespace {
// A 64-bit hash of a matrix's bits (FNV-1a over its floats, then a final mix): equal matrices hash equal.
uint64_t hashOfMatrix(const glm::mat4& m) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) h = (h ^ std::bit_cast<uint32_t>(m[c][r])) * 0x100000001b3ull;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  return h ^ (h >> 33);
}
}  // namespace

ShadowPass::ShadowPass(VulkanContext& ctx, const Settings& settings) : ctx_(ctx), settings_(settings) {
  Pipeline::GraphicsDesc d;
  d.vertex = DYNGI_SHADER(spv_shadow_vert);
  d.fragment = DYNGI_SHADER(spv_shadow_frag);
  setMeshVertexInput(d, /*normal=*/false, /*uv=*/false);
  d.colorFormats = {VK_FORMAT_R32_SFLOAT};
  d.depthFormat = VK_FORMAT_D32_SFLOAT;
  d.pushConstantBytes = sizeof(gpu::ShadowPush);
  d.bindings = {{DYNGI_SHADOW_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}};
  // The depth bias is applied in shadow_depth.glsl (to the depth test and the lookup alike), as floats' bits.
  d.fragmentSpecialization = {std::bit_cast<uint32_t>(settings.depthBiasConstant), std::bit_cast<uint32_t>(settings.depthBiasSlope)};
  d.name = "shadow";
  pipeline_ = Pipeline::graphics(ctx, d);
  // Alpha-masked casters (glTF alphaMode MASK): their own variant, so opaque ones pay no texture lookup.
  d.vertex = DYNGI_SHADER(spv_shadow_masked_vert);
  d.fragment = DYNGI_SHADER(spv_shadow_masked_frag);
  setMeshVertexInput(d, /*normal=*/false, /*uv=*/true);
  d.bindings.push_back({DYNGI_SHADOW_BINDING_BASE_COLOR_TEX, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT});
  d.name = "shadow_masked";
  maskedPipeline_ = Pipeline::graphics(ctx, d);

  lights_ = Buffer(ctx, sizeof(gpu::GpuLight) * DYNGI_MAX_LIGHTS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "lights");
  matrices_ = Buffer(ctx, sizeof(glm::mat4) * settings.maxLayers, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "shadow matrices");
  layers_ = makeLayers(1, "shadow map");  // grown to the layers the lights use (execute())
  ctx.immediate([&](VkCommandBuffer cmd) {  // readable before the first shadow is drawn: nothing casts
    layers_.lookup.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue far{{1.0f, 0.0f, 0.0f, 0.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
    vkCmdClearColorImage(cmd, layers_.lookup.handle(), VK_IMAGE_LAYOUT_GENERAL, &far, 1, &all);
  });
}

ShadowPass::Layers ShadowPass::makeLayers(uint32_t count, const char* name) const {
  ImageDesc id;
  id.width = id.height = settings_.mapSize;
  id.layers = count;
  id.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  id.name = name;
  Layers l;
  id.format = VK_FORMAT_D32_SFLOAT;
  id.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  l.depth = Image(ctx_, id);
  id.format = VK_FORMAT_R32_SFLOAT;
  id.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  l.lookup = Image(ctx_, id);
  return l;
}

void ShadowPass::prepareForDrawing(VkCommandBuffer cmd, Layers& layers) const {
  layers.depth.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  layers.lookup.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                           VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

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

void ShadowPass::drawCasters(VkCommandBuffer cmd, const Layers& target, uint32_t layer, const glm::mat4& viewProj, const FrameContext& frame,
                             const std::vector<size_t>& draws, bool clear) {
  const uint32_t size = settings_.mapSize;
  const VkAttachmentLoadOp load = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  RenderingScope rendering(cmd, size, size, {colorAttachment(target.lookup.layerView(layer), {{1.0f, 0.0f, 0.0f, 0.0f}}, load)},
                           depthAttachment(target.depth.layerView(layer), load));
  const gpu::ShadowPush pc{viewProj};
  drawBatched(
      frame, draws, [&](const DrawItem& d) -> const Pipeline& { return frame.snapshot.materialOf(d).alphaMask ? maskedPipeline_ : pipeline_; },
      [&](VkCommandBuffer c, const DrawItem& d, const Pipeline& p) {
        DescriptorWrites writes;
        writes.storageBuffer(DYNGI_SHADOW_BINDING_INSTANCES, frame.instances->records->handle());
        if (frame.snapshot.materialOf(d).alphaMask)
          writes.sampledImage(DYNGI_SHADOW_BINDING_BASE_COLOR_TEX, frame.textureView(frame.snapshot.materialOf(d).baseColorTexture), frame.linearSampler,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        writes.push(ctx_, c, p);
        vkCmdPushConstants(c, p.layout(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(pc), &pc);
      });
}

std::optional<VkRect2D> ShadowPass::movingFootprint(const glm::mat4& viewProj, const FrameContext& frame,
                                                    const std::vector<size_t>& draws) const {
  const float size = float(settings_.mapSize);
  glm::vec2 lo(size), hi(0.0f);
  for (size_t i : draws) {
    const DrawItem& d = frame.snapshot.draws[i];
    const scene::Aabb& b = frame.snapshot.assets->mesh(d.mesh).bounds;
    if (!b.valid()) return std::nullopt;
    const glm::mat4 m = viewProj * d.model;
    for (int c = 0; c < 8; ++c) {
      glm::vec4 clip = m * glm::vec4((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z, 1.0f);
      if (clip.w <= 1e-6f) return std::nullopt;  // reaches behind the light: no bounded footprint
      glm::vec2 texel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size;
      lo = glm::min(lo, texel);
      hi = glm::max(hi, texel);
    }
  }
  // Two texels of margin for rasterization rounding; clamped to the map (empty when off the map).
  const glm::ivec2 first = glm::clamp(glm::ivec2(glm::floor(lo)) - 2, glm::ivec2(0), glm::ivec2(int(size)));
  const glm::ivec2 end = glm::clamp(glm::ivec2(glm::ceil(hi)) + 2, glm::ivec2(0), glm::ivec2(int(size)));
  const glm::ivec2 extent = glm::max(end - first, glm::ivec2(0));
  return VkRect2D{{first.x, first.y}, {uint32_t(extent.x), uint32_t(extent.y)}};
}

void ShadowPass::execute(FrameContext& frame) {
  ++frameCounter_;
  CasterSets sets = gatherCasters(frame);
  // The layers grow to what the lights use (memory for one spot is one layer, not maxLayers); all are
  // drawn again then. Frames are synchronous, so no command buffer still reads the old images.
  if (layerMatrices_.size() > layers_.count()) {
    layers_ = makeLayers(uint32_t(layerMatrices_.size()), "shadow map");
    renderedMatrices_.clear();
  }
  movingRects_.resize(layers_.count());
  LayerPlan plan = planLayers(sets);
  layersRendered_ = uint32_t(plan.direct.size() + plan.fromCache.size());
  if (rendered_ && layersRendered_ == 0) return;  // the shadow map is current
  rendered_ = true;
  renderedCasters_ = std::move(sets.casters);
  renderedMatrices_ = layerMatrices_;

  ScopedPass scope(ctx_, frame.timer, frame.cmd, kName);
  VkCommandBuffer cmd = frame.cmd;
  if (!plan.cacheRebuild.empty()) rebuildStaticCache(frame, sets, plan);
  if (!plan.fromCache.empty()) restoreFromCache(frame, sets, plan);
  for (uint32_t layer : plan.direct) movingRects_[layer].reset();  // drawn whole: not the cache plus movers
  prepareForDrawing(cmd, layers_);
  for (uint32_t layer : plan.direct) drawCasters(cmd, layers_, layer, layerMatrices_[layer], frame, sets.all, true);
  for (uint32_t layer : plan.fromCache) drawCasters(cmd, layers_, layer, layerMatrices_[layer], frame, sets.moving, false);
  layers_.lookup.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

// Casters, and which of them moved, turned or deformed lately (the first sight of one is no change).
// Last frame's casters are usually the same entities in the same order: each is compared with the one
// at its place, and looked up by entity only when that is another. Only casters that changed are
// remembered with the frame they changed at.
ShadowPass::CasterSets ShadowPass::gatherCasters(const FrameContext& frame) {
  CasterSets sets;
  std::unordered_map<scene::Entity, const Caster*> before;  // built on the first caster out of place
  auto previous = [&](size_t place, scene::Entity e) -> const Caster* {
    if (place < renderedCasters_.size() && renderedCasters_[place].entity == e) return &renderedCasters_[place];
    if (before.empty())
      for (const Caster& c : renderedCasters_) before[c.entity] = &c;
    const auto it = before.find(e);
    return it == before.end() ? nullptr : it->second;
  };
  sets.casters.reserve(frame.snapshot.draws.size());
  for (size_t i = 0; i < frame.snapshot.draws.size(); ++i) {
    const DrawItem& d = frame.snapshot.draws[i];
    const GpuMesh* mesh = frame.meshes[i];
    if (!d.castShadows || !mesh || mesh->indexCount == 0) continue;
    Caster c{d.entity, d.mesh, mesh->version, hashOfMatrix(d.model)};
    const Caster* was = previous(sets.casters.size(), d.entity);
    uint64_t changedAt = 0;
    if (rendered_ && (!was || !(*was == c))) changedAt = casterChangedAt_[d.entity] = frameCounter_;
    else if (const auto it = casterChangedAt_.find(d.entity); it != casterChangedAt_.end()) changedAt = it->second;
    sets.casters.push_back(c);
    sets.all.push_back(i);
    const bool isMoving = changedAt > 0 && frameCounter_ - changedAt < kSettleFrames;
    (isMoving ? sets.moving : sets.statics).push_back(i);
    if (!isMoving) sets.staticCasters.push_back(c);
  }
  if (casterChangedAt_.size() > 2 * sets.casters.size() + 64) {  // forget casters that are gone
    std::unordered_map<scene::Entity, uint64_t> kept;
    for (const Caster& c : sets.casters)
      if (const auto it = casterChangedAt_.find(c.entity); it != casterChangedAt_.end()) kept[c.entity] = it->second;
    casterChangedAt_ = std::move(kept);
  }
  return sets;
}

// Per layer: kept (nothing it shows changed), redrawn whole (its light view changed, or no caster moves),
// or rebuilt from the cached static casters plus the moving ones (light still, casters moving).
ShadowPass::LayerPlan ShadowPass::planLayers(const CasterSets& sets) const {
  LayerPlan plan;
  const bool castersChanged = !rendered_ || sets.casters != renderedCasters_;
  for (uint32_t layer = 0; layer < layerMatrices_.size(); ++layer) {
    const bool viewSame = layer < renderedMatrices_.size() && renderedMatrices_[layer] == layerMatrices_[layer];
    if (rendered_ && viewSame && !castersChanged) continue;
    if (!viewSame || sets.moving.empty()) {
      plan.direct.push_back(layer);
      continue;
    }
    plan.fromCache.push_back(layer);
    if (layer >= cacheMatrices_.size() || cacheMatrices_[layer] != layerMatrices_[layer] || cacheCasters_[layer] != sets.staticCasters)
      plan.cacheRebuild.push_back(layer);
  }
  return plan;
}

// The static casters' layers the cache lacks, drawn into it (the whole cache when it had to grow).
void ShadowPass::rebuildStaticCache(FrameContext& frame, const CasterSets& sets, LayerPlan& plan) {
  const uint32_t layersInUse = uint32_t(layerMatrices_.size());
  if (staticCache_.count() < layersInUse) {
    staticCache_ = makeLayers(layersInUse, "shadow static cache");
    cacheMatrices_.clear();
    cacheCasters_.clear();
    plan.cacheRebuild = plan.fromCache;  // the old cache is gone
  }
  cacheMatrices_.resize(layersInUse, glm::mat4(0.0f));
  cacheCasters_.resize(layersInUse);
  prepareForDrawing(frame.cmd, staticCache_);
  for (uint32_t layer : plan.cacheRebuild) {
    drawCasters(frame.cmd, staticCache_, layer, layerMatrices_[layer], frame, sets.statics, true);
    cacheMatrices_[layer] = layerMatrices_[layer];
    cacheCasters_[layer] = sets.staticCasters;
  }
}

// The layers drawn from the cache get back, per layer, where the moving casters were drawn last frame
// and where they are now (the rest of the layer is the cache already), or the whole layer.
void ShadowPass::restoreFromCache(FrameContext& frame, const CasterSets& sets, const LayerPlan& plan) {
  VkCommandBuffer cmd = frame.cmd;
  for (Image* img : {&staticCache_.depth, &staticCache_.lookup})
    img->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  for (Image* img : {&layers_.depth, &layers_.lookup})
    img->transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  std::vector<VkRect2D> restore;
  for (uint32_t layer : plan.fromCache) {
    std::optional<VkRect2D> now = movingFootprint(layerMatrices_[layer], frame, sets.moving);
    const bool cacheRedrawn = std::find(plan.cacheRebuild.begin(), plan.cacheRebuild.end(), layer) != plan.cacheRebuild.end();
    VkRect2D r{{0, 0}, {settings_.mapSize, settings_.mapSize}};
    if (now && movingRects_[layer] && !cacheRedrawn) {
      const VkRect2D& was = *movingRects_[layer];
      const int32_t x0 = std::min(was.offset.x, now->offset.x), y0 = std::min(was.offset.y, now->offset.y);
      const int32_t x1 = std::max(was.offset.x + int32_t(was.extent.width), now->offset.x + int32_t(now->extent.width));
      const int32_t y1 = std::max(was.offset.y + int32_t(was.extent.height), now->offset.y + int32_t(now->extent.height));
      r = VkRect2D{{x0, y0}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
    }
    restore.push_back(r);
    movingRects_[layer] = now;
  }
  for (VkImageAspectFlags aspect : {VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT), VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT)}) {
    std::vector<VkImageCopy> regions;
    for (size_t k = 0; k < plan.fromCache.size(); ++k) {
      if (restore[k].extent.width == 0 || restore[k].extent.height == 0) continue;
      VkImageCopy c{};
      c.srcSubresource = {aspect, 0, plan.fromCache[k], 1};
      c.dstSubresource = {aspect, 0, plan.fromCache[k], 1};
      c.srcOffset = c.dstOffset = {restore[k].offset.x, restore[k].offset.y, 0};
      c.extent = {restore[k].extent.width, restore[k].extent.height, 1};
      regions.push_back(c);
    }
    if (regions.empty()) continue;
    const bool depth = aspect == VK_IMAGE_ASPECT_DEPTH_BIT;
    vkCmdCopyImage(cmd, (depth ? staticCache_.depth : staticCache_.lookup).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   (depth ? layers_.depth : layers_.lookup).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()), regions.data());
  }
}

}  // namespace dyngi::render
