#include "techniques/many_lights/many_lights.h"

#include <algorithm>
#include <cstring>

#include "dyngi/engine/render/draw_pass.h"
#include "dyngi/engine/render/light_views.h"
#include "techniques/many_lights/shaders/many_lights_shared.h"
#include "indirect/indirect_passes.h"
#include "indirect/reduced_screen.h"
#include "spirv/many_lights_debug.comp.spv.h"
#include "spirv/rsm.frag.spv.h"
#include "spirv/rsm.vert.spv.h"
#include "spirv/rsm_tangent.vert.spv.h"
#include "spirv/vpl_bounce.comp.spv.h"
#include "spirv/vpl_cdf_rows.comp.spv.h"
#include "spirv/vpl_cdf_total.comp.spv.h"
#include "spirv/vpl_sample.comp.spv.h"
#include "spirv/vpl_tail.comp.spv.h"

#include "gpu_aliases.h"
#include "sampling.h"
#include "indirect/emitters.h"
#include "camera_focus.h"

namespace dyngi::gi {

ManyLights::ManyLights(render::VulkanContext& ctx, VoxelScene& voxels, const ManyLightsOptions& settings)
    : ctx_(ctx), voxels_(voxels), settings_(settings) {
  // The values used from here on (Technique::options() reports them): bounces and K clamped, the VPL
  // count rounded to a multiple of the bounces.
  settings_.vpl.bounces = std::clamp(settings_.vpl.bounces, 1u, 3u);
  tailStride_ = std::clamp(settings_.vpl.bounceTailStride, 1u, 4u);
  // Bounced VPLs (and the bounce tail's probes) take the albedo and normal of the voxel they land on.
  if (settings_.vpl.bounces > 1 || settings_.vpl.bounceTail) voxels_.enableLeafAttributes();
  settings_.vpl.interleave = std::clamp(settings_.vpl.interleave, 1u, 8u);
  settings_.vpl.vpls = settings_.vpl.effectiveVplCount();
  const Binding rowsB[] = {{DYNGI_VPL_CDF_ROWS_BINDING_RSM_FLUX, kSampled, kCS},
                           {DYNGI_VPL_CDF_ROWS_BINDING_ROW_PREFIX, kSSBO, kCS},
                           {DYNGI_VPL_CDF_ROWS_BINDING_ROW_SUMS, kSSBO, kCS}};
  cdfRows_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_vpl_cdf_rows_comp), rowsB, sizeof(gpu::VplCdfRowsPush), "vpl_cdf_rows");
  const Binding totalB[] = {{DYNGI_VPL_CDF_TOTAL_BINDING_ROW_SUMS, kSSBO, kCS}};
  cdfTotal_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_vpl_cdf_total_comp), totalB, sizeof(gpu::VplCdfTotalPush), "vpl_cdf_total");
  const Binding sampleB[] = {{DYNGI_VPL_SAMPLE_BINDING_RSM_POSITION, kSampled, kCS},
                             {DYNGI_VPL_SAMPLE_BINDING_RSM_NORMAL, kSampled, kCS},
                             {DYNGI_VPL_SAMPLE_BINDING_RSM_FLUX, kSampled, kCS},
                             {DYNGI_VPL_SAMPLE_BINDING_ROW_PREFIX, kSSBO, kCS},
                             {DYNGI_VPL_SAMPLE_BINDING_ROW_CDF, kSSBO, kCS},
                             {DYNGI_VPL_SAMPLE_BINDING_VPLS, kSSBO, kCS}};
  sample_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_vpl_sample_comp), sampleB, sizeof(gpu::VplSamplePush), "vpl_sample");
  const Binding bounceB[] = {{DYNGI_VPL_BOUNCE_BINDING_VPLS, kSSBO, kCS},
                             {DYNGI_VPL_BOUNCE_BINDING_NODES, kSSBO, kCS},
                             {DYNGI_VPL_BOUNCE_BINDING_NODE_CELLS, kSSBO, kCS},
                             {DYNGI_VPL_BOUNCE_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS}};
  bounce_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_vpl_bounce_comp), bounceB, sizeof(gpu::VplBouncePush), "vpl_bounce");
  const Binding tailB[] = {{DYNGI_VPL_TAIL_BINDING_VPLS, kSSBO, kCS}};
  tail_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_vpl_tail_comp), tailB, sizeof(gpu::VplTailPush), "vpl_tail");
  gatherPass_ = std::make_unique<IndirectGatherPass>(ctx);
  reduced_ = std::make_unique<ReducedScreen>(ctx);
  filterPass_ = std::make_unique<IndirectFilterPass>(ctx);
  const Binding debugB[] = {{DYNGI_MANY_LIGHTS_DEBUG_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS},
                            {DYNGI_MANY_LIGHTS_DEBUG_BINDING_G_ALBEDO, kSampled, kCS},
                            {DYNGI_MANY_LIGHTS_DEBUG_BINDING_RAW, kStorageImage, kCS},
                            {DYNGI_MANY_LIGHTS_DEBUG_BINDING_VPLS, kSSBO, kCS},
                            {DYNGI_MANY_LIGHTS_DEBUG_BINDING_HDR, kStorageImage, kCS}};
  debug_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_many_lights_debug_comp), debugB, sizeof(gpu::ManyLightsDebugPush), "many_lights_debug");

  lights_ = Buffer(ctx, sizeof(::dyngi::gpu::GpuLight) * DYNGI_MAX_LIGHTS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "rsm lights");
  layers_ = Buffer(ctx, sizeof(gpu::RsmLayer) * DYNGI_MAX_RSM_LAYERS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "rsm layers");
}

ManyLights::~ManyLights() = default;

static_assert(sizeof(gpu::GpuVpl) == 48, "ManyLights::EmitterVpl mirrors gpu::GpuVpl");

void ManyLights::prepareEmitters(const render::RenderSnapshot& snapshot, const scene::AssetStore& assets) {
  emitterVpls_.clear();
  const EmitterSet emitters(snapshot, assets);
  if (emitters.empty()) return;
  float lightsPower = 0.0f;
  const scene::Aabb sunBounds = cameraFocus(snapshot, settings_.vpl.directionalReach).bounds;
  for (const render::LightItem& l : snapshot.lights) lightsPower += lightPower(l, sunBounds);
  const uint32_t bounces = std::clamp(settings_.vpl.bounces, 1u, 3u), perBounce = vplCount() / bounces;
  // The emitters' share of the first bounce, at least one VPL while they emit, and one left to the RSMs
  // while a light does.
  const float share = emitters.totalPower() / (emitters.totalPower() + lightsPower);
  uint32_t n = std::max(1u, uint32_t(std::lround(share * float(perBounce))));
  if (lightsPower > 0.0f) n = std::min(n, perBounce - 1);
  for (uint32_t k = 0; k < n; ++k) {
    uint64_t h = mix64(uint64_t(settings_.vpl.seed) * 0x9E3779B97F4A7C15ULL + k);
    auto next = [&h] { h = mix64(h + 0x632BE59BD9B4E019ULL); return float(h >> 40) * (1.0f / 16777216.0f); };
    const float u0 = (float(k) + next()) / float(n);  // stratified over the emitters' power
    const EmitterSample e = emitters.sample(u0, next(), next(), next());
    EmitterVpl v{glm::vec4(0, 0, 0, -1), glm::vec4(0, 1, 0, 0), glm::vec4(0.0f)};
    if (!e.entity.isNull()) {
      const glm::vec3 flux = e.flux / float(n);
      v.position = glm::vec4(e.position, 0.0f);  // bounce 0: the source itself
      v.normal = glm::vec4(e.normal, 0.0f);
      v.flux = glm::vec4(flux, emitterLuminance(flux));
    }
    emitterVpls_.push_back(v);
  }
}

void ManyLights::ensureRsm(uint32_t layers) {
  layers = std::max(layers, 1u);
  uint32_t res = settings_.rsmResolution;
  if (rsmLayers_ >= layers && rsmPosition_.valid() && rsmPosition_.desc().width == res) return;
  vkDeviceWaitIdle(ctx_.device());
  auto make = [&](VkFormat f, VkImageUsageFlags usage, const char* name) {
    render::ImageDesc d;
    d.width = d.height = res;
    d.layers = layers;
    d.format = f;
    d.usage = usage;
    d.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    d.name = name;
    return Image(ctx_, d);
  };
  constexpr VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  rsmPosition_ = make(VK_FORMAT_R32G32B32A32_SFLOAT, color, "rsm position");
  rsmNormal_ = make(VK_FORMAT_R16G16B16A16_SFLOAT, color, "rsm normal");
  rsmFlux_ = make(VK_FORMAT_R32G32B32A32_SFLOAT, color, "rsm flux");
  rsmDepth_ = make(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "rsm depth");
  rowPrefix_ = Buffer(ctx_, VkDeviceSize(res) * res * layers * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "vpl row prefix");
  rowCdf_ = Buffer(ctx_, VkDeviceSize(res) * layers * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "vpl row cdf");
  rsmLayers_ = layers;
}

void ManyLights::resize(render::VulkanContext& ctx, uint32_t width, uint32_t height) {
  width_ = width;
  height_ = height;
  render::ImageDesc d;
  d.width = ReducedScreen::reducedSize(width, gatherScale());
  d.height = ReducedScreen::reducedSize(height, gatherScale());
  d.format = VK_FORMAT_R32G32B32A32_UINT;  // filter_input.glsl's packing: light with depth and normal
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "indirect raw (interleaved)";
  raw_ = Image(ctx, d);
}

bool ManyLights::screenReduced() const { return ReducedScreen::reduces(width_, height_, gatherScale()); }

void ManyLights::prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) {
  if (raw_.valid() && (raw_.desc().width != ReducedScreen::reducedSize(width_, gatherScale()) ||
                       raw_.desc().height != ReducedScreen::reducedSize(height_, gatherScale())))
    resize(ctx, width_, height_);  // a GI budget moved the gather scale
  settings_.vpl.bounces = std::clamp(settings_.vpl.bounces, 1u, 3u);
  settings_.vpl.interleave = std::clamp(settings_.vpl.interleave, 1u, 8u);
  perBounce_ = vplCount() / settings_.vpl.bounces;  // the one rounding rule (VplOptions::effectiveVplCount)
  std::vector<::dyngi::gpu::GpuLight> lights;
  std::vector<gpu::RsmLayer> layers;
  // A directional light's RSM covers its focus (camera_focus.h), seen from outside the scene.
  const CameraFocus focus = cameraFocus(snapshot, settings_.vpl.directionalReach);
  for (const render::LightItem& item : snapshot.lights) {
    if (lights.size() >= DYNGI_MAX_LIGHTS) break;
    if (!item.light.enabled || item.light.intensity <= 0.0f) continue;
    auto views = render::lightViews(item, snapshot.sceneBounds, focus.wholeScene ? nullptr : &focus.bounds);
    if (layers.size() + views.size() > DYNGI_MAX_RSM_LAYERS) break;
    for (const auto& v : views) {
      gpu::RsmLayer l{};
      l.viewProj = v.viewProj;
      l.axis = glm::vec4(v.axis, v.extent);
      l.lightIndex = uint32_t(lights.size());
      l.orthographic = v.orthographic ? 1u : 0u;
      l.resolution = settings_.rsmResolution;
      layers.push_back(l);
    }
    lights.push_back(render::toGpuLight(item));
  }
  rsmLayersUsed_ = uint32_t(layers.size());
  ensureRsm(rsmLayersUsed_);
  if (!lights.empty()) lights_.upload(lights.data(), lights.size() * sizeof(lights[0]));
  if (!layers.empty()) layers_.upload(layers.data(), layers.size() * sizeof(layers[0]));
  // With the bounce tail, one more bounce: the probes, gathered with the rest.
  VkDeviceSize vplBytes = VkDeviceSize(gatheredVplCount()) * sizeof(gpu::GpuVpl);
  if (!vpls_.valid() || vpls_.size() < vplBytes)
    vpls_ = Buffer(ctx_, vplBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuOnly, "vpls");
  // The emitters' VPLs close the first bounce: [perBounce - n, perBounce) (prepareEmitters sized them
  // with this frame's VPL count).
  if (emitterVpls_.size() > perBounce_) emitterVpls_.resize(perBounce_);
  for (uint32_t k = 0; k < emitterVpls_.size(); ++k) emitterVpls_[k].normal.w = float(perBounce_ - uint32_t(emitterVpls_.size()) + k);
  const VkDeviceSize emitterBytes = emitterVpls_.size() * sizeof(EmitterVpl);
  if (emitterBytes > 0) {
    if (!emitterUpload_.valid() || emitterUpload_.size() < emitterBytes)
      emitterUpload_ = Buffer(ctx_, emitterBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "emitter vpls");
    emitterUpload_.upload(emitterVpls_.data(), emitterBytes);
  }
}

render::Pipeline& ManyLights::rsmPipelineFor(uint32_t textureBits) {
  const bool baseColorTexture = textureBits & DYNGI_MATERIAL_BASE_COLOR_TEX, mrTexture = textureBits & DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX;
  const bool alphaMask = textureBits & DYNGI_MATERIAL_ALPHA_MASK, normalTexture = textureBits & DYNGI_MATERIAL_NORMAL_TEX;
  Pipeline& pipeline = rsm_[(baseColorTexture ? 1 : 0) | (mrTexture ? 2 : 0) | (alphaMask ? 4 : 0) | (normalTexture ? 8 : 0)];
  if (pipeline.handle()) return pipeline;
  Pipeline::GraphicsDesc d;
  d.vertex = normalTexture ? DYNGI_SHADER(spv_rsm_tangent_vert) : DYNGI_SHADER(spv_rsm_vert);
  d.fragment = DYNGI_SHADER(spv_rsm_frag);
  render::setMeshVertexInput(d, /*normal=*/true, /*uv=*/true);
  if (normalTexture) render::setMeshTangentInput(d);
  d.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT};
  d.depthFormat = VK_FORMAT_D32_SFLOAT;
  d.pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  d.pushConstantBytes = sizeof(gpu::RsmPush);
  d.bindings = {{DYNGI_RSM_BINDING_LAYERS, kSSBO, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_RSM_BINDING_INSTANCES, kSSBO, VK_SHADER_STAGE_VERTEX_BIT},
                {DYNGI_RSM_BINDING_LIGHTS, kSSBO, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_RSM_BINDING_BASE_COLOR_TEX, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_RSM_BINDING_METALLIC_ROUGHNESS_TEX, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
                {DYNGI_RSM_BINDING_NORMAL_TEX, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT}};
  d.fragmentSpecialization = {baseColorTexture ? 1u : 0u, mrTexture ? 1u : 0u, alphaMask ? 1u : 0u, normalTexture ? 1u : 0u};
  d.name = "rsm";
  pipeline = Pipeline::graphics(ctx_, d);
  return pipeline;
}

bool ManyLights::record(render::FrameContext& frame) {
  if (!voxels_.hasVolume() || !raw_.valid()) return false;
  recordReflectiveShadowMaps(frame);
  recordVplGeneration(frame);
  recordVplBounces(frame);
  recordGatherAndFilter(frame);
  return true;
}

// "rsm": one reflective shadow map layer per light view (position, normal, flux).
void ManyLights::recordReflectiveShadowMaps(render::FrameContext& frame) {
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t res = settings_.rsmResolution;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "rsm");
  for (Image* img : {&rsmPosition_, &rsmNormal_, &rsmFlux_})
    img->transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  rsmDepth_.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                       VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                       VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  for (uint32_t layer = 0; layer < rsmLayers_; ++layer) {
    // Unused layers are cleared too: their flux must read as zero.
    render::RenderingScope rendering(cmd, res, res,
                                     {render::colorAttachment(rsmPosition_.layerView(layer)), render::colorAttachment(rsmNormal_.layerView(layer)),
                                      render::colorAttachment(rsmFlux_.layerView(layer))},
                                     render::depthAttachment(rsmDepth_.layerView(layer), VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE));
    if (layer < rsmLayersUsed_) {
      auto pipelineFor = [&](const render::DrawItem& dr) -> const Pipeline& {
        return rsmPipelineFor(render::drawTextureBits(frame, dr));
      };
      const gpu::RsmPush pc{layer};
      render::drawBatched(frame, std::nullopt, pipelineFor, [&](VkCommandBuffer c, const render::DrawItem& dr, const Pipeline& pipeline) {
        DescriptorWrites()
            .storageBuffer(DYNGI_RSM_BINDING_LAYERS, layers_.handle())
            .storageBuffer(DYNGI_RSM_BINDING_LIGHTS, lights_.handle())
            .storageBuffer(DYNGI_RSM_BINDING_INSTANCES, frame.instances->records->handle())
            .sampledImage(DYNGI_RSM_BINDING_BASE_COLOR_TEX, frame.textureView(frame.snapshot.materialOf(dr).baseColorTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_RSM_BINDING_METALLIC_ROUGHNESS_TEX, frame.textureView(frame.snapshot.materialOf(dr).metallicRoughnessTexture), frame.linearSampler,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_RSM_BINDING_NORMAL_TEX, frame.textureView(frame.snapshot.materialOf(dr).normalTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .push(ctx_, c, pipeline);
        vkCmdPushConstants(c, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
      });
    }
  }
  for (Image* img : {&rsmPosition_, &rsmNormal_, &rsmFlux_})
    img->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

// "vpl_generate": the first bounce's VPLs, importance-sampled from the RSM flux (row CDFs, then samples),
// then the emitters' VPLs sampled on the CPU after them.
void ManyLights::recordVplGeneration(render::FrameContext& frame) {
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t res = settings_.rsmResolution;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "vpl_generate");
  constexpr VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  uint32_t rows = res * rsmLayers_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cdfRows_.handle());
  DescriptorWrites()
      .sampledImage(DYNGI_VPL_CDF_ROWS_BINDING_RSM_FLUX, rsmFlux_.view(), frame.nearestSampler, ro)
      .storageBuffer(DYNGI_VPL_CDF_ROWS_BINDING_ROW_PREFIX, rowPrefix_.handle())
      .storageBuffer(DYNGI_VPL_CDF_ROWS_BINDING_ROW_SUMS, rowCdf_.handle())
      .push(ctx_, cmd, cdfRows_);
  const gpu::VplCdfRowsPush rp{res, rsmLayers_};
  vkCmdPushConstants(cmd, cdfRows_.layout(), kCS, 0, sizeof(rp), &rp);
  vkCmdDispatch(cmd, dispatchGroups(rows, 64), 1, 1);
  render::computeWriteBarrier(cmd);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cdfTotal_.handle());
  DescriptorWrites().storageBuffer(DYNGI_VPL_CDF_TOTAL_BINDING_ROW_SUMS, rowCdf_.handle()).push(ctx_, cmd, cdfTotal_);
  const gpu::VplCdfTotalPush tp{rows};
  vkCmdPushConstants(cmd, cdfTotal_.layout(), kCS, 0, sizeof(tp), &tp);
  vkCmdDispatch(cmd, 1, 1, 1);
  render::computeWriteBarrier(cmd);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sample_.handle());
  DescriptorWrites()
      .sampledImage(DYNGI_VPL_SAMPLE_BINDING_RSM_POSITION, rsmPosition_.view(), frame.nearestSampler, ro)
      .sampledImage(DYNGI_VPL_SAMPLE_BINDING_RSM_NORMAL, rsmNormal_.view(), frame.nearestSampler, ro)
      .sampledImage(DYNGI_VPL_SAMPLE_BINDING_RSM_FLUX, rsmFlux_.view(), frame.nearestSampler, ro)
      .storageBuffer(DYNGI_VPL_SAMPLE_BINDING_ROW_PREFIX, rowPrefix_.handle())
      .storageBuffer(DYNGI_VPL_SAMPLE_BINDING_ROW_CDF, rowCdf_.handle())
      .storageBuffer(DYNGI_VPL_SAMPLE_BINDING_VPLS, vpls_.handle())
      .push(ctx_, cmd, sample_);
  const uint32_t fromEmitters = uint32_t(emitterVpls_.size()), fromLights = perBounce_ - fromEmitters;
  const gpu::VplSamplePush sp{res, rsmLayers_, fromLights, settings_.vpl.seed * 7919u};
  vkCmdPushConstants(cmd, sample_.layout(), kCS, 0, sizeof(sp), &sp);
  if (fromLights > 0) vkCmdDispatch(cmd, dispatchGroups(fromLights, 64), 1, 1);
  if (fromEmitters > 0) {  // the emitters' VPLs, sampled on the CPU, after the lights'
    const VkBufferCopy region{0, VkDeviceSize(fromLights) * sizeof(gpu::GpuVpl), VkDeviceSize(fromEmitters) * sizeof(gpu::GpuVpl)};
    vkCmdCopyBuffer(cmd, emitterUpload_.handle(), vpls_.handle(), 1, &region);
  }
  render::computeWriteBarrier(cmd);  // compute and transfer writes
}

// "vpl_bounce": each further bounce through the voxel scene, then the bounce tail's probes.
void ManyLights::recordVplBounces(render::FrameContext& frame) {
  const uint32_t bounces = settings_.vpl.bounces;
  if (bounces <= 1 && !settings_.vpl.bounceTail) return;
  VkCommandBuffer cmd = frame.cmd;
  const VoxelVolume& vol = voxels_.volume();
  render::ScopedPass scope(ctx_, frame.timer, cmd, "vpl_bounce");
  // Bounces 2..B, then with the tail its probes as bounce B + 1 (one parent per run of tailStride_).
  for (uint32_t b = 1; b < bounces + (settings_.vpl.bounceTail ? 1u : 0u); ++b) {
    const uint32_t stride = b == bounces ? tailStride_ : 1u;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bounce_.handle());
    DescriptorWrites()
        .storageBuffer(DYNGI_VPL_BOUNCE_BINDING_VPLS, vpls_.handle())
        .storageBuffer(DYNGI_VPL_BOUNCE_BINDING_NODES, voxels_.nodes().handle())
        .storageBuffer(DYNGI_VPL_BOUNCE_BINDING_NODE_CELLS, voxels_.nodeCells().handle())
        .storageImage(DYNGI_VPL_BOUNCE_BINDING_VOXEL_ATTRIBUTES, voxels_.voxelAttributes().view())
        .push(ctx_, cmd, bounce_);
    const gpu::VplBouncePush pc{glm::vec4(vol.origin, 1.0f / vol.voxelSize), (b - 1) * perBounce_, perBounce_, b, vol.depth(),
                                float(vol.resolution), settings_.vpl.liftVoxels, settings_.vpl.seed, stride};
    vkCmdPushConstants(cmd, bounce_.layout(), kCS, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, dispatchGroups((perBounce_ + stride - 1) / stride, 64), 1, 1);
    render::computeWriteBarrier(cmd);
  }
  if (settings_.vpl.bounceTail) {  // the probes' bounce, gathered, carries every later one (vpl_tail.comp)
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tail_.handle());
    DescriptorWrites().storageBuffer(DYNGI_VPL_TAIL_BINDING_VPLS, vpls_.handle()).push(ctx_, cmd, tail_);
    const gpu::VplTailPush tp{(bounces - 1) * perBounce_, perBounce_, tailProbeCount()};
    vkCmdPushConstants(cmd, tail_.layout(), kCS, 0, sizeof(tp), &tp);
    vkCmdDispatch(cmd, 1, 1, 1);
    render::computeWriteBarrier(cmd);
  }
}

// "indirect", "filter": the interleaved gather with SVO visibility, then the merge and geometry-aware filter.
void ManyLights::recordGatherAndFilter(render::FrameContext& frame) {
  const uint32_t K = settings_.vpl.interleave;
  const uint32_t vplTotal = gatheredVplCount();
  const VoxelVolume& vol = voxels_.volume();
  IndirectGatherPass::Inputs in;
  in.vpls = vpls_.handle();
  in.nodes = voxels_.nodes().handle();
  in.bits = vpls_.handle();  // unused: SVO visibility or none
  gpu::GatherPush& pc = in.push;
  pc.worldToVoxel = glm::vec4(vol.origin, 1.0f / vol.voxelSize);
  pc.distanceClamp = settings_.vpl.distanceClamp;
  pc.clampSpread = settings_.vpl.clampSpreadStretch();
  pc.tailBounce = settings_.vpl.bounceTail ? settings_.vpl.bounces : 0u;  // the probes' bounce (recordVplBounces)
  pc.luminanceThreshold = settings_.vpl.luminanceThreshold;
  pc.liftVoxels = settings_.vpl.liftVoxels;
  pc.voxelResolution = float(vol.resolution);
  pc.vplCount = vplTotal;
  pc.estimatedCount = vplTotal;  // every VPL of the frame is gathered (its flux is its share of the lights')
  pc.interleave = K;
  pc.visibility = settings_.visibility == VisibilityBackend::Svo ? DYNGI_VISIBILITY_SVO : DYNGI_VISIBILITY_NONE;
  pc.svoDepth = vol.depth();
  render::FrameContext& screen = reduced_->begin(frame, gatherScale());
  gatherPass_->record(screen, raw_, in);
  filterPass_->record(screen, raw_, K, settings_.vpl);
  reduced_->finish(frame);
}

void ManyLights::recordAfterLighting(render::FrameContext& frame) {
  if (settings_.view == ManyLightsView::Final || !raw_.valid()) return;
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "many_lights_debug_view");
  render::RenderTargets& t = frame.targets;
  t.hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  raw_.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, debug_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_MANY_LIGHTS_DEBUG_BINDING_FRAME, frame.frameUniforms.handle())
      .sampledImage(DYNGI_MANY_LIGHTS_DEBUG_BINDING_G_ALBEDO, t.albedo.view(), frame.nearestSampler)
      .storageImage(DYNGI_MANY_LIGHTS_DEBUG_BINDING_RAW, raw_.view())
      .storageBuffer(DYNGI_MANY_LIGHTS_DEBUG_BINDING_VPLS, vpls_.handle())
      .storageImage(DYNGI_MANY_LIGHTS_DEBUG_BINDING_HDR, t.hdr.view())
      .push(ctx_, frame.cmd, debug_);
  const uint32_t mode = settings_.view == ManyLightsView::Vpls ? 0u : 1u;
  const uint32_t vplTotal = gatheredVplCount();
  const gpu::ManyLightsDebugPush pc{mode, settings_.vpl.interleave, vplTotal};
  vkCmdPushConstants(frame.cmd, debug_.layout(), kCS, 0, sizeof(pc), &pc);
  const uint32_t n = mode == 0 ? vplTotal : t.width * t.height;
  vkCmdDispatch(frame.cmd, dispatchGroups(n, 64), 1, 1);
}

}  // namespace dyngi::gi
