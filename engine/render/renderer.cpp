#include "dyngi/engine/render/renderer.h"

#include <chrono>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "dyngi/engine/render/draw_pass.h"
#include "dyngi/engine/render/frame_uniforms.h"
#include "shared/gpu_types.h"
#include "passes/passes.h"

namespace dyngi::render {
namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

Image makeTarget(VulkanContext& ctx, uint32_t w, uint32_t h, VkFormat f, VkImageUsageFlags usage, const char* name) {
  ImageDesc d;
  d.width = w;
  d.height = h;
  d.format = f;
  d.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = name;
  return Image(ctx, d);
}
}  // namespace

Renderer::Renderer(VulkanContext& ctx, const RendererSettings& settings) : ctx_(ctx), settings_(settings) {
  // Members clean up after themselves; the raw handles below are released here if a later step throws.
  try {
    create();
  } catch (...) {
    releaseHandles();
    throw;
  }
}

void Renderer::create() {
  VulkanContext& ctx = ctx_;
  const RendererSettings& settings = settings_;
  frameUniforms_ = Buffer(ctx, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Upload, "frame uniforms");
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  DYNGI_VK(vkCreateSampler(ctx.device(), &sci, ctx.allocator(), &linearSampler_));
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  DYNGI_VK(vkCreateSampler(ctx.device(), &sci, ctx.allocator(), &nearestSampler_));

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx.queueFamily();
  DYNGI_VK(vkCreateCommandPool(ctx.device(), &pci, ctx.allocator(), &pool_));
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  DYNGI_VK(vkAllocateCommandBuffers(ctx.device(), &ai, &cmd_));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  DYNGI_VK(vkCreateFence(ctx.device(), &fci, ctx.allocator(), &fence_));

  const uint8_t white[4] = {255, 255, 255, 255};
  whiteTexture_ = createTexture(ctx, 1, 1, white, false, "white");
  if (settings.gpuTimestamps) timer_ = std::make_unique<GpuTimer>(ctx, settings.stageTiming);
  shadow_ = std::make_unique<ShadowPass>(ctx, ShadowPass::Settings{.mapSize = settings.shadowMapSize, .maxLayers = settings.maxShadowLayers});
  gbuffer_ = std::make_unique<GBufferPass>(ctx);
  lighting_ = std::make_unique<LightingPass>(ctx);
  tonemap_ = std::make_unique<TonemapPass>(ctx);
}

Renderer::~Renderer() { releaseHandles(); }

void Renderer::setStageTiming(GpuTimer::Mode mode) {
  if (!timer_) return;
  if (mode == GpuTimer::Mode::Fenced && hostFramePending_) throw VulkanError("a host's frame cannot be timed by fences");
  timer_->setMode(mode);
}

void Renderer::releaseHandles() {
  vkDeviceWaitIdle(ctx_.device());
  if (fence_) vkDestroyFence(ctx_.device(), fence_, ctx_.allocator());
  if (pool_) vkDestroyCommandPool(ctx_.device(), pool_, ctx_.allocator());
  if (linearSampler_) vkDestroySampler(ctx_.device(), linearSampler_, ctx_.allocator());
  if (nearestSampler_) vkDestroySampler(ctx_.device(), nearestSampler_, ctx_.allocator());
  fence_ = VK_NULL_HANDLE;
  pool_ = VK_NULL_HANDLE;
  linearSampler_ = nearestSampler_ = VK_NULL_HANDLE;
}

bool Renderer::resize(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) return false;
  if (width == targets_.width && height == targets_.height) return true;
  if (width > 16384 || height > 16384) throw VulkanError("render size too large: " + std::to_string(width) + "x" + std::to_string(height));
  vkDeviceWaitIdle(ctx_.device());
  constexpr VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
  constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  RenderTargets& t = targets_;
  t.width = width;
  t.height = height;
  t.position = makeTarget(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, color, "gbuffer position");
  t.normal = makeTarget(ctx_, width, height, VK_FORMAT_R16G16B16A16_SFLOAT, color, "gbuffer normal");
  t.albedo = makeTarget(ctx_, width, height, VK_FORMAT_R8G8B8A8_UNORM, color, "gbuffer albedo");
  t.emissive = makeTarget(ctx_, width, height, VK_FORMAT_R16G16B16A16_SFLOAT, color, "gbuffer emissive");
  t.depth = makeTarget(ctx_, width, height, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "depth");
  t.indirect = makeTarget(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "indirect");
  t.specular = makeTarget(ctx_, width, height, VK_FORMAT_R16G16B16A16_SFLOAT, storage, "indirect specular");
  t.hdr = makeTarget(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "hdr");
  // The display image is also a colour attachment: overlays (RenderFeature::recordOverlay) draw on it.
  t.ldr = makeTarget(ctx_, width, height, VK_FORMAT_R8G8B8A8_UNORM, storage | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "ldr");
  for (RenderFeature* f : features_) f->resize(ctx_, width, height);
  return true;
}

GpuMesh* Renderer::meshFor(const scene::AssetStore& assets, scene::MeshId id) {
  if (meshesOf_ != &assets) {  // a new scene: drop the old scene's GPU meshes and textures
    vkDeviceWaitIdle(ctx_.device());
    meshes_.clear();
    textures_.clear();
    meshesOf_ = &assets;
  }
  const scene::MeshData& m = assets.mesh(id);
  GpuMesh& g = meshes_[id];
  if (g.vertices.valid() && g.version == m.version) return &g;
  std::vector<GpuVertex> verts(m.positions.size());
  for (size_t i = 0; i < verts.size(); ++i) {
    std::memcpy(verts[i].position, &m.positions[i], 12);
    glm::vec3 n = i < m.normals.size() ? m.normals[i] : glm::vec3(0, 1, 0);
    std::memcpy(verts[i].normal, &n, 12);
    glm::vec2 uv = i < m.uvs.size() ? m.uvs[i] : glm::vec2(0.0f);
    std::memcpy(verts[i].uv, &uv, 8);
  }
  VkDeviceSize vbytes = verts.size() * sizeof(GpuVertex), ibytes = m.indices.size() * sizeof(uint32_t);
  if (!g.vertices.valid() || g.vertices.size() < vbytes)
    g.vertices = Buffer(ctx_, vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "mesh vertices");
  if (!g.indices.valid() || g.indices.size() < ibytes)
    g.indices = Buffer(ctx_, ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "mesh indices");
  g.vertices.upload(verts.data(), vbytes);
  if (m.tangents.size() == m.positions.size() && !m.tangents.empty()) {
    const VkDeviceSize tbytes = m.tangents.size() * sizeof(glm::vec4);
    if (!g.tangents.valid() || g.tangents.size() < tbytes)
      g.tangents = Buffer(ctx_, tbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, MemoryUsage::GpuOnly, "mesh tangents");
    g.tangents.upload(m.tangents.data(), tbytes);
  } else {
    g.tangents.reset();
  }
  g.indices.upload(m.indices.data(), ibytes);
  g.indexCount = uint32_t(m.indices.size());
  g.version = m.version;
  return &g;
}

VkImageView Renderer::textureView(const scene::AssetStore& assets, scene::TextureId id) {
  if (id == scene::kNoTexture || id >= assets.textureCount()) return whiteTexture_.view();
  auto it = textures_.find(id);
  if (it == textures_.end()) {
    const scene::TextureData& t = assets.texture(id);
    if (t.width == 0 || t.height == 0 || t.rgba8.size() < size_t(t.width) * t.height * 4) return whiteTexture_.view();
    it = textures_.emplace(id, createTexture(ctx_, t.width, t.height, t.rgba8.data(), t.srgb, t.name.c_str())).first;
  }
  return it->second.view();
}

const FrameStats& Renderer::render(const RenderSnapshot& snapshot, Swapchain* swapchain) {
  stats_ = {};
  if (targets_.width == 0) throw VulkanError("Renderer::render called before resize()");
  auto t0 = Clock::now();
  // Uploads first (they submit their own one-off work), then record the frame.
  const std::vector<GpuMesh*> meshes = uploadAssets(snapshot);
  buildFrameInstances(ctx_, snapshot, meshes, drawInstances_, frameInstances_);
  auto textures = [&](scene::TextureId id) { return snapshot.assets ? textureView(*snapshot.assets, id) : whiteTexture_.view(); };
  for (RenderFeature* f : features_) f->prepare(ctx_, snapshot);
  shadow_->prepare(snapshot);
  const gpu::FrameUniforms fu = uploadFrameUniforms(snapshot);
  uint32_t imageIndex = UINT32_MAX;
  if (swapchain && swapchain->valid()) imageIndex = swapchain->acquire();
  beginCommands();
  auto submitAndWait = [this] { submitAndWaitMidFrame(); };
  if (timer_) timer_->beginFrame(cmd_, submitAndWait);
  FrameContext frame{ctx_, cmd_, timer_.get(), snapshot, targets_, frameUniforms_, fu, meshes, linearSampler_, nearestSampler_, textures,
                     submitAndWait};
  frame.lights = LightInputs{&shadow_->lights(), &shadow_->matrices(), &shadow_->shadowMap(), shadow_->lightCount()};
  frame.instances = &frameInstances_;
  recordPasses(frame, textures);
  if (imageIndex != UINT32_MAX && !settings_.featuresOnly) recordPresentBlit(*swapchain, imageIndex);
  DYNGI_VK(vkEndCommandBuffer(cmd_));
  submitFrame(swapchain, imageIndex, t0);
  for (RenderFeature* f : features_) f->frameFinished(ctx_);
  return stats_;
}

// The meshes whose version changed and the textures the draws use, uploaded before recording starts.
std::vector<GpuMesh*> Renderer::uploadAssets(const RenderSnapshot& snapshot) {
  std::vector<GpuMesh*> meshes(snapshot.draws.size(), nullptr);
  if (!snapshot.assets) return meshes;
  for (size_t i = 0; i < snapshot.draws.size(); ++i) meshes[i] = meshFor(*snapshot.assets, snapshot.draws[i].mesh);
  for (const scene::Material& m : snapshot.materials)
    for (scene::TextureId id : {m.baseColorTexture, m.emissiveTexture, m.metallicRoughnessTexture, m.occlusionTexture, m.normalTexture})
      textureView(*snapshot.assets, id);
  return meshes;
}

gpu::FrameUniforms Renderer::uploadFrameUniforms(const RenderSnapshot& snapshot) {
  gpu::FrameUniforms fu = cameraUniforms(snapshot.camera, targets_.width, targets_.height);
  fu.sizeAndCount = glm::uvec4(targets_.width, targets_.height, shadow_->lightCount(), uint32_t(snapshot.frame));
  fu.exposure = glm::vec4(settings_.exposure, float(settings_.toneMapper), 0, 0);
  fu.background = glm::vec4(settings_.background, 0.0f);
  frameUniforms_.upload(&fu, sizeof(fu));
  return fu;
}

void Renderer::beginCommands() {
  DYNGI_VK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  DYNGI_VK(vkBeginCommandBuffer(cmd_, &bi));
}

// What FrameContext::submitAndWait does: the frame so far, submitted and waited for, then recording goes
// on in the same command buffer (fenced stage timing; Embree visibility reading the G-buffer).
void Renderer::submitAndWaitMidFrame() {
  DYNGI_VK(vkEndCommandBuffer(cmd_));
  VkCommandBufferSubmitInfo part{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  part.commandBuffer = cmd_;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &part;
  DYNGI_VK(vkResetFences(ctx_.device(), 1, &fence_));
  DYNGI_VK(vkQueueSubmit2(ctx_.queue(), 1, &si, fence_));
  DYNGI_VK(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  VkCommandBufferBeginInfo again{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  again.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  DYNGI_VK(vkBeginCommandBuffer(cmd_, &again));
}

// shadow, gbuffer, the features, lighting, the features' views, tonemap, the overlays.
void Renderer::recordPasses(FrameContext& frame, const std::function<VkImageView(scene::TextureId)>& textures) {
  if (!settings_.featuresOnly) {
    shadow_->execute(frame);
    gbuffer_->execute(frame, textures);
  }
  bool indirectWritten = false;
  for (RenderFeature* f : features_) indirectWritten |= f->record(frame);
  if (settings_.featuresOnly) return;
  clearIndirectIfUnwritten(cmd_, indirectWritten);
  lighting_->execute(frame, *shadow_, indirectWritten, frame.specular);
  for (RenderFeature* f : features_) f->recordAfterLighting(frame);
  tonemap_->execute(frame);
  for (RenderFeature* f : features_) f->recordOverlay(frame);
}

// Readable as a target: zero, not last frame's.
void Renderer::clearIndirectIfUnwritten(VkCommandBuffer cmd, bool written) {
  if (written) return;
  targets_.indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkClearColorValue zero{};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, targets_.indirect.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
}

const FrameStats& Renderer::recordHostFrame(const RenderSnapshot& snapshot, VkCommandBuffer cmd,
                                            const std::function<void(FrameContext&)>& fillGBuffer,
                                            const std::function<void(FrameContext&)>& afterFeatures) {
  if (targets_.width == 0) throw VulkanError("Renderer::recordHostFrame called before resize()");
  if (timer_ && timer_->mode() == GpuTimer::Mode::Fenced) throw VulkanError("a host's frame cannot be timed by fences (--stage-times fenced)");
  stats_ = {};
  if (hostFramePending_) {
    if (timer_) {
      timer_->resolve(/*wait=*/false);
      stats_.gpuMs = timer_->results();
    stats_.gpuMsTimestamps = timer_->timestampResults();
    }
    for (RenderFeature* f : features_) f->frameFinished(ctx_);
  }
  auto t0 = Clock::now();
  const std::vector<GpuMesh*> meshes = uploadAssets(snapshot);
  buildFrameInstances(ctx_, snapshot, meshes, drawInstances_, frameInstances_);
  auto textures = [&](scene::TextureId id) { return snapshot.assets ? textureView(*snapshot.assets, id) : whiteTexture_.view(); };
  for (RenderFeature* f : features_) f->prepare(ctx_, snapshot);
  shadow_->prepare(snapshot);
  const gpu::FrameUniforms fu = uploadFrameUniforms(snapshot);
  if (timer_) timer_->beginFrame(cmd, {});
  auto noWait = [] { throw VulkanError("this technique reads the frame back mid-frame, which a host's frame cannot (use SVO visibility)"); };
  FrameContext frame{ctx_, cmd, timer_.get(), snapshot, targets_, frameUniforms_, fu, meshes, linearSampler_, nearestSampler_, textures, noWait};
  frame.lights = LightInputs{&shadow_->lights(), &shadow_->matrices(), &shadow_->shadowMap(), shadow_->lightCount()};
  frame.instances = &frameInstances_;
  shadow_->execute(frame);
  fillGBuffer(frame);
  bool indirectWritten = false;
  for (RenderFeature* f : features_) indirectWritten |= f->record(frame);
  clearIndirectIfUnwritten(cmd, indirectWritten);
  afterFeatures(frame);
  stats_.cpuRecordMs = msSince(t0);
  hostFramePending_ = true;
  return stats_;
}

// The display image blitted to the swapchain image. Not fenced: a submission before the last would
// write the swapchain image before it is acquired.
void Renderer::recordPresentBlit(Swapchain& swapchain, uint32_t imageIndex) {
  ScopedPass scope(ctx_, timer_ && timer_->mode() == GpuTimer::Mode::Timestamps ? timer_.get() : nullptr, cmd_, "present_blit");
  targets_.ldr.transition(cmd_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkImage sw = swapchain.image(imageIndex);
  const VkImageSubresourceRange colour{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  auto swBarrier = [&](VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcS, VkAccessFlags2 srcA, VkPipelineStageFlags2 dstS,
                       VkAccessFlags2 dstA) { imageBarrier(cmd_, sw, colour, from, to, srcS, srcA, dstS, dstA); };
  swBarrier(VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
            VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkExtent2D ext = swapchain.extent();
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(targets_.width), int32_t(targets_.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {int32_t(ext.width), int32_t(ext.height), 1};
  vkCmdBlitImage(cmd_, targets_.ldr.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, sw, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
  swBarrier(VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
}

// The frame submitted (waiting on the swapchain image, signalling its presentation), waited for,
// presented, and its pass times resolved.
void Renderer::submitFrame(Swapchain* swapchain, uint32_t imageIndex, Clock::time_point recordStart) {
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd_;
  VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  VkSemaphoreSubmitInfo signalInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  if (imageIndex != UINT32_MAX) {
    waitInfo.semaphore = swapchain->acquiredSemaphore();
    waitInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    signalInfo.semaphore = swapchain->renderedSemaphore();
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &waitInfo;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signalInfo;
  }
  DYNGI_VK(vkResetFences(ctx_.device(), 1, &fence_));
  DYNGI_VK(vkQueueSubmit2(ctx_.queue(), 1, &si, fence_));
  stats_.cpuRecordMs = msSince(recordStart);
  auto t1 = Clock::now();
  DYNGI_VK(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  stats_.cpuWaitMs = msSince(t1);
  if (imageIndex != UINT32_MAX) stats_.presented = swapchain->present(imageIndex);
  if (timer_) {
    timer_->resolve();
    stats_.gpuMs = timer_->results();
    stats_.gpuMsTimestamps = timer_->timestampResults();
  }
}

Image& Renderer::target(TargetId id) {
  switch (id) {
    case TargetId::Position: return targets_.position;
    case TargetId::Normal: return targets_.normal;
    case TargetId::Albedo: return targets_.albedo;
    case TargetId::Emissive: return targets_.emissive;
    case TargetId::Depth: return targets_.depth;
    case TargetId::Indirect: return targets_.indirect;
    case TargetId::Specular: return targets_.specular;
    case TargetId::Hdr: return targets_.hdr;
    case TargetId::Ldr: return targets_.ldr;
  }
  return targets_.hdr;
}

std::vector<glm::vec4> Renderer::readback(TargetId id) { return readbackImage(ctx_, target(id)); }

std::vector<uint8_t> Renderer::readbackLdr() { return readbackImageBytes(ctx_, targets_.ldr); }

}  // namespace dyngi::render
