#include "techniques/vct/voxel_cone_tracing.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <optional>

#include "dyngi/engine/render/gpu_timer.h"
#include "gpu_aliases.h"
#include "techniques/vct/shaders/vct_shared.h"
#include "spirv/vct_bounce.comp.spv.h"
#include "spirv/vct_clear_stale.comp.spv.h"
#include "spirv/vct_commit.comp.spv.h"
#include "spirv/vct_cone_probe.comp.spv.h"
#include "spirv/vct_debug.comp.spv.h"
#include "spirv/vct_emitter_light.comp.spv.h"
#include "spirv/vct_filter.comp.spv.h"
#include "spirv/vct_inject.comp.spv.h"
#include "spirv/vct_mips.comp.spv.h"
#include "spirv/vct_reproject.comp.spv.h"
#include "spirv/vct_trace.comp.spv.h"
#include "spirv/vct_upsample.comp.spv.h"

namespace dyngi::gi {

namespace {
constexpr VkFormat kRadianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkImageUsageFlags kVolumeUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
constexpr VkPipelineStageFlags2 kComputeAndTransfer = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
constexpr VkAccessFlags2 kReadWrite = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;

Image makeVolume(render::VulkanContext& ctx, uint32_t w, uint32_t h, uint32_t d, uint32_t mips, const char* name,
                 VkFormat format = kRadianceFormat) {
  render::ImageDesc desc;
  desc.width = w;
  desc.height = h;
  desc.depth = d;
  desc.mips = mips;
  desc.format = format;
  desc.usage = kVolumeUsage;
  desc.viewType = VK_IMAGE_VIEW_TYPE_3D;
  desc.name = name;
  return Image(ctx, desc);
}

uint64_t volumeBytes(const Image& img) {
  if (!img.valid()) return 0;
  uint64_t bytes = 0;
  const auto& d = img.desc();
  for (uint32_t m = 0; m < d.mips; ++m)
    bytes += uint64_t(std::max(d.width >> m, 1u)) * std::max(d.height >> m, 1u) * std::max(d.depth >> m, 1u) * render::formatBytesPerPixel(d.format);
  return bytes;
}

void clearLevel(VkCommandBuffer cmd, Image& img, uint32_t mip) {
  const VkClearColorValue zero{};
  const VkImageSubresourceRange level{VK_IMAGE_ASPECT_COLOR_BIT, mip, 1, 0, 1};
  vkCmdClearColorImage(cmd, img.handle(), img.layout(), &zero, 1, &level);
}

// The nodes of an SVO level (its leaves at level depth) are visited by an indirect dispatch sized by the
// build (SvoLevel::dispatch).
constexpr VkDeviceSize levelDispatchOffset(uint32_t level) {
  return VkDeviceSize(level) * sizeof(gpu::SvoLevel) + offsetof(gpu::SvoLevel, dispatch);
}

// A cell's Morton code (svo_morton.glsl's svoMortonCode).
uint32_t mortonCode(glm::uvec3 cell) {
  uint32_t code = 0;
  for (uint32_t bit = 0; bit < 10; ++bit)
    for (uint32_t axis = 0; axis < 3; ++axis) code |= ((cell[axis] >> bit) & 1u) << (3 * bit + axis);
  return code;
}

// The runs of 32 consecutive Morton codes (4 x 4 x 2 cells) of SVO level `level` that cover the cells
// lo..hi (inclusive) of that level.
void appendRuns(std::vector<glm::uvec2>& runs, uint32_t level, glm::uvec3 lo, glm::uvec3 hi) {
  for (uint32_t z = lo.z / 2; z <= hi.z / 2; ++z)
    for (uint32_t y = lo.y / 4; y <= hi.y / 4; ++y)
      for (uint32_t x = lo.x / 4; x <= hi.x / 4; ++x) runs.push_back(glm::uvec2(level, mortonCode(glm::uvec3(4 * x, 4 * y, 2 * z))));
}
}  // namespace

VctOptions VoxelConeTracing::validated(VctOptions o) {
  o.bounces = std::clamp(o.bounces, 1u, 3u);
  o.diffuseCones = std::max(o.diffuseCones, 1u);
  o.traceFrames = std::bit_floor(std::clamp(o.traceFrames, 1u, 4u));
  o.diffuseFilterRadius = std::min(o.diffuseFilterRadius, VctOptions::kMaxDiffuseFilterRadius);
  // Without the filter nothing brings the rows' cone sets together: every pixel marches all of them.
  o.coneInterleave = o.diffuseFilterRadius > 0 ? std::clamp(o.coneInterleave, 1u, o.diffuseCones) : 1u;
  o.temporalResponse = std::max(o.temporalResponse, 1e-3f);
  o.emitterSamples = o.emitterSamples > 0 ? std::bit_floor(std::min(o.emitterSamples, uint32_t(DYNGI_VCT_EMITTER_MAX_SAMPLES))) : 0u;
  o.emitterFrames = std::clamp(o.emitterFrames, 1u, 64u);
  return o;
}

VoxelConeTracing::VoxelConeTracing(render::VulkanContext& ctx, VoxelScene& voxels, const VctOptions& options)
    : ctx_(ctx), voxels_(voxels), options_(validated(options)) {
  voxels_.enableLeafAttributes();  // albedo, normal and emission per voxel: what injection lights
  createLeafPipelines();
  createMipsPipelines();
  createScreenPipelines();
  createSampler();
  changedBoxes_ = Buffer(ctx_, 2 * kMaxChangedBoxes * sizeof(glm::uvec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "vct changed boxes");
  emitterPoints_ = Buffer(ctx_, DYNGI_VCT_EMITTER_POINTS * sizeof(gpu::VctEmitterPoint), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "vct emitter points");
}

// The passes over the occupied voxels: injection, clearing what emptied, the bounce and its commit.
void VoxelConeTracing::createLeafPipelines() {
  const Binding leafB[] = {{DYNGI_VCT_INJECT_BINDING_LEAF_LIST, kSSBO, kCS},
                           {DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS},
                           {DYNGI_VCT_INJECT_BINDING_LIGHTS, kSSBO, kCS},
                           {DYNGI_VCT_INJECT_BINDING_SHADOW_MATRICES, kSSBO, kCS},
                           {DYNGI_VCT_INJECT_BINDING_SHADOW_MAPS, kStorageImage, kCS},
                           {DYNGI_VCT_INJECT_BINDING_DIRECT, kStorageImage, kCS},
                           {DYNGI_VCT_INJECT_BINDING_RADIANCE, kStorageImage, kCS},
                           {DYNGI_VCT_INJECT_BINDING_CHANGED_BOXES, kSSBO, kCS},
                           {DYNGI_VCT_INJECT_BINDING_CARRIED, kStorageImage, kCS}};
  inject_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_inject_comp), leafB, sizeof(gpu::VctInjectPush), "vct_inject");
  const Binding clearB[] = {{DYNGI_VCT_CLEAR_BINDING_RUNS, kSSBO, kCS},          {DYNGI_VCT_CLEAR_BINDING_PREVIOUS_OCCUPANCY, kSSBO, kCS},
                            {DYNGI_VCT_CLEAR_BINDING_OCCUPANCY, kSSBO, kCS},     {DYNGI_VCT_CLEAR_BINDING_RADIANCE, kStorageImage, kCS},
                            {DYNGI_VCT_CLEAR_BINDING_DIRECT, kStorageImage, kCS}, {DYNGI_VCT_CLEAR_BINDING_ATLAS, kStorageImage, kCS},
                            {DYNGI_VCT_CLEAR_BINDING_ATLAS_1, kStorageImage, kCS}, {DYNGI_VCT_CLEAR_BINDING_CARRIED, kStorageImage, kCS}};
  clearStale_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_clear_stale_comp), clearB, sizeof(gpu::VctClearPush), "vct_clear_stale");
  const Binding bounceB[] = {{DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST, kSSBO, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_DIRECT, kStorageImage, kCS}, {DYNGI_VCT_BOUNCE_BINDING_RADIANCE, kSampled, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_ANISO, kSampled, kCS},    {DYNGI_VCT_BOUNCE_BINDING_OUT, kStorageImage, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_CHANGED_BOXES, kSSBO, kCS}, {DYNGI_VCT_BOUNCE_BINDING_PREVIOUS_OCCUPANCY, kSSBO, kCS}};
  const Binding commitB[] = {{DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST, kSSBO, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_DIRECT, kStorageImage, kCS},
                             {DYNGI_VCT_BOUNCE_BINDING_OUT, kStorageImage, kCS}};
  commit_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_commit_comp), commitB, sizeof(gpu::VctBouncePush), "vct_commit");
  const Binding emitterB[] = {{DYNGI_VCT_EMITTER_BINDING_LEAF_LIST, kSSBO, kCS},     {DYNGI_VCT_EMITTER_BINDING_VOXEL_ATTRIBUTES, kStorageImage, kCS},
                              {DYNGI_VCT_EMITTER_BINDING_OUT, kStorageImage, kCS},   {DYNGI_VCT_EMITTER_BINDING_CHANGED_BOXES, kSSBO, kCS},
                              {DYNGI_VCT_EMITTER_BINDING_PREVIOUS_OCCUPANCY, kSSBO, kCS}, {DYNGI_VCT_EMITTER_BINDING_SVO_NODES, kSSBO, kCS},
                              {DYNGI_VCT_EMITTER_BINDING_POINTS, kSSBO, kCS}};
  emitterLight_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_emitter_light_comp), emitterB, sizeof(gpu::VctEmitterPush), "vct_emitter_light");
  const Binding probeB[] = {{DYNGI_VCT_PROBE_BINDING_RAYS, kSSBO, kCS},
                            {DYNGI_VCT_PROBE_BINDING_RADIANCE, kSampled, kCS},
                            {DYNGI_VCT_PROBE_BINDING_ANISO, kSampled, kCS},
                            {DYNGI_VCT_PROBE_BINDING_RESULTS, kSSBO, kCS}};
  for (bool aniso : {false, true})
    for (bool unitStep : {false, true}) {
      const ConeVariant v{aniso, unitStep};
      const uint32_t spec[] = {aniso ? 1u : 0u, 0u, unitStep ? 1u : 0u};  // constant 1 is vct_bounce.comp's kCarried; 2 is vct_cone.glsl's kVctUnitStep
      bounce_[v.index()] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_bounce_comp), bounceB, sizeof(gpu::VctBouncePush), "vct_bounce", spec);
      const uint32_t carrySpec[] = {aniso ? 1u : 0u, 1u, unitStep ? 1u : 0u};
      carry_[v.index()] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_bounce_comp), bounceB, sizeof(gpu::VctBouncePush), "vct_carry", carrySpec);
      probe_[v.index()] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_cone_probe_comp), probeB, sizeof(gpu::VctProbePush), "vct_cone_probe", spec);
    }
}

// vct_mips.comp's variants: (anisotropic, opaque axis, atlas level 0, its source the direct radiance).
void VoxelConeTracing::createMipsPipelines() {
  const Binding mipsB[] = {{DYNGI_VCT_MIPS_BINDING_SOURCE, kStorageImage, kCS},     {DYNGI_VCT_MIPS_BINDING_DEST, kStorageImage, kCS},
                           {DYNGI_VCT_MIPS_BINDING_SEEN, kStorageImage, kCS},
                           {DYNGI_VCT_MIPS_BINDING_NODE_CELLS, kSSBO, kCS},         {DYNGI_VCT_MIPS_BINDING_LEVELS, kSSBO, kCS},
                           {DYNGI_VCT_MIPS_BINDING_LEAF_LIST, kSSBO, kCS},          {DYNGI_VCT_MIPS_BINDING_CHANGED_BOXES, kSSBO, kCS}};
  const std::pair<MipsVariant, std::array<uint32_t, 4>> variants[] = {
      {MipsVariant::Isotropic, {0u, 0u, 0u, 0u}},       {MipsVariant::Atlas, {1u, 0u, 0u, 0u}},
      {MipsVariant::IsotropicOpaqueAxis, {0u, 1u, 0u, 0u}}, {MipsVariant::AtlasFromLevel0, {1u, 0u, 1u, 0u}},
      {MipsVariant::AtlasFromDirect, {1u, 0u, 1u, 1u}}};
  for (const auto& [variant, spec] : variants)
    mips_[uint32_t(variant)] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_mips_comp), mipsB, sizeof(gpu::VctMipsPush), "vct_mips", spec);
}

// The screen's passes: trace, reproject, filter, upsample, and the debug views.
void VoxelConeTracing::createScreenPipelines() {
  const Binding traceB[] = {{DYNGI_VCT_TRACE_BINDING_FRAME, kUBO, kCS},
                            {DYNGI_VCT_TRACE_BINDING_G_POSITION, kStorageImage, kCS},
                            {DYNGI_VCT_TRACE_BINDING_G_NORMAL, kStorageImage, kCS},
                            {DYNGI_VCT_TRACE_BINDING_RADIANCE, kSampled, kCS},
                            {DYNGI_VCT_TRACE_BINDING_ANISO, kSampled, kCS},
                            {DYNGI_VCT_TRACE_BINDING_OUT_DIFFUSE, kStorageImage, kCS},
                            {DYNGI_VCT_TRACE_BINDING_OUT_SPECULAR, kStorageImage, kCS}};
  const Binding debugB[] = {{DYNGI_VCT_DEBUG_BINDING_FRAME, kUBO, kCS},          {DYNGI_VCT_DEBUG_BINDING_RADIANCE, kSampled, kCS},
                            {DYNGI_VCT_DEBUG_BINDING_ANISO, kSampled, kCS},       {DYNGI_VCT_DEBUG_BINDING_INDIRECT, kStorageImage, kCS},
                            {DYNGI_VCT_DEBUG_BINDING_SPECULAR, kStorageImage, kCS}, {DYNGI_VCT_DEBUG_BINDING_OUT_HDR, kStorageImage, kCS}};
  for (bool aniso : {false, true}) {
    const uint32_t spec[] = {aniso ? 1u : 0u};
    debug_[aniso ? 1 : 0] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_debug_comp), debugB, sizeof(gpu::VctDebugPush), "vct_debug", spec);
    for (bool specular : {false, true})
      for (bool unitStep : {false, true}) {
        const uint32_t traceSpec[] = {aniso ? 1u : 0u, specular ? 1u : 0u, unitStep ? 1u : 0u};  // vct_trace.comp's, then kVctUnitStep
        trace_[TraceVariant{aniso, specular, unitStep}.index()] =
            render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_trace_comp), traceB, sizeof(gpu::VctTracePush), "vct_trace", traceSpec);
      }
  }
  const Binding upB[] = {{DYNGI_VCT_UPSAMPLE_BINDING_G_POSITION, kStorageImage, kCS}, {DYNGI_VCT_UPSAMPLE_BINDING_G_NORMAL, kStorageImage, kCS},
                         {DYNGI_VCT_UPSAMPLE_BINDING_LOW_DIFFUSE, kStorageImage, kCS}, {DYNGI_VCT_UPSAMPLE_BINDING_LOW_SPECULAR, kStorageImage, kCS},
                         {DYNGI_VCT_UPSAMPLE_BINDING_OUT_DIFFUSE, kStorageImage, kCS}, {DYNGI_VCT_UPSAMPLE_BINDING_OUT_SPECULAR, kStorageImage, kCS},
                         {DYNGI_VCT_UPSAMPLE_BINDING_FRAME, kUBO, kCS}, {DYNGI_VCT_UPSAMPLE_BINDING_LOW_SURFACE, kStorageImage, kCS}};
  for (bool specular : {false, true}) {
    const uint32_t spec[] = {specular ? 1u : 0u};
    upsample_[specular ? 1 : 0] = render::LazyPipeline::compute(ctx_, DYNGI_SHADER(spv_vct_upsample_comp), upB, sizeof(gpu::VctUpsamplePush), "vct_upsample", spec);
  }
  const Binding reprojectB[] = {{DYNGI_VCT_REPROJECT_BINDING_FRAME, kUBO, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_G_POSITION, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_G_NORMAL, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_DIFFUSE, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SPECULAR, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SURFACE, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_OUT_DIFFUSE, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_OUT_SPECULAR, kStorageImage, kCS},
                                {DYNGI_VCT_REPROJECT_BINDING_OUT_SURFACE, kStorageImage, kCS}};
  reproject_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_reproject_comp), reprojectB, sizeof(gpu::VctReprojectPush), "vct_reproject");
  const Binding filterB[] = {{DYNGI_VCT_FILTER_BINDING_FRAME, kUBO, kCS},
                             {DYNGI_VCT_FILTER_BINDING_SURFACE, kStorageImage, kCS},
                             {DYNGI_VCT_FILTER_BINDING_IN, kStorageImage, kCS},
                             {DYNGI_VCT_FILTER_BINDING_OUT, kStorageImage, kCS}};
  filter_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_vct_filter_comp), filterB, sizeof(gpu::VctFilterPush), "vct_filter");
}

// Quadrilinear, clamped to the edge: a coarse texel at the volume's side (a floor, a wall near it) is
// continued past it rather than faded to nothing, which would make a cone see half of it. A cone stops
// when it leaves the volume (vct_cone.glsl), so nothing beyond is sampled.
void VoxelConeTracing::createSampler() {
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = VK_LOD_CLAMP_NONE;
  DYNGI_VK(vkCreateSampler(ctx_.device(), &si, ctx_.allocator(), &sampler_));
}

VoxelConeTracing::~VoxelConeTracing() {
  if (sampler_) vkDestroySampler(ctx_.device(), sampler_, ctx_.allocator());
}

void VoxelConeTracing::ensureVolumes(uint32_t res) {
  const bool wantAniso = options_.anisotropic;
  // Kept once emitters were seen, so an emission switched on and off does not remake the volumes.
  const bool wantBounce = options_.bounces > 1, wantCarried = options_.bounceFrames > 0 || (options_.emitterSamples > 0 && emittersSeen_);
  if (res == res_ && aniso_.valid() == wantAniso && bounced_.valid() == wantBounce && carried_.valid() == wantCarried) return;
  vkDeviceWaitIdle(ctx_.device());
  const uint32_t levels = uint32_t(std::bit_width(res));  // res, res/2, ..., 1
  if (res != res_) {
    radiance_ = makeVolume(ctx_, res, res, res, levels, "vct radiance");
    direct_ = makeVolume(ctx_, res, res, res, 1, "vct direct radiance");
    frames_ = 0;
  }
  const uint32_t half = std::max(res / 2, 1u);
  aniso_ = wantAniso ? makeVolume(ctx_, DYNGI_VCT_SLABS * half, half, half, uint32_t(std::bit_width(half)), "vct anisotropic atlas") : Image();
  bounced_ = wantBounce ? makeVolume(ctx_, res, res, res, 1, "vct bounced radiance") : Image();
  carried_ = wantCarried ? makeVolume(ctx_, res, res, res, 1, "vct carried light") : Image();
  res_ = res;
  frames_ = 0;  // the volumes are new: nothing of theirs to keep
  ctx_.immediate([&](VkCommandBuffer cmd) {
    for (Image* img : {&radiance_, &aniso_, &direct_, &bounced_, &carried_}) {
      if (!img->valid()) continue;
      img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const VkClearColorValue zero{};
      const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, 1};
      vkCmdClearColorImage(cmd, img->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    }
  });
  stats_.volumeBytes = volumeBytes(radiance_) + volumeBytes(aniso_) + volumeBytes(direct_) + volumeBytes(bounced_) + volumeBytes(carried_);
}

uint32_t VoxelConeTracing::radianceParts() const { return std::clamp(std::max(options_.radianceFrames, budgetRadianceParts_), 1u, 4u); }

uint32_t VoxelConeTracing::traceScale() const {
  uint32_t base = options_.traceScale;
  if (base == 0) {
    base = 1;
    while (base < kMaxTraceScale && uint64_t(width_ / base) * (height_ / base) > kAutoTracePixels) base *= 2;
  }
  return std::min(base * budgetFactor_, kMaxTraceScale);
}

void VoxelConeTracing::ensureTraceTargets(uint32_t width, uint32_t height) {
  width_ = width;
  height_ = height;
  const uint32_t s = traceScale();
  const uint32_t w = std::max((width + s - 1) / s, 1u), h = std::max((height + s - 1) / s, 1u);
  if (tracedScale_ == s && filteredDiffuse_.valid() && filteredDiffuse_.desc().width == w && filteredDiffuse_.desc().height == h) return;
  vkDeviceWaitIdle(ctx_.device());
  tracedScale_ = s;
  traceHistory_ = false;
  render::ImageDesc d;
  d.width = w;
  d.height = h;
  d.format = kRadianceFormat;
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  for (TracedPixels& t : traced_) {
    d.format = kRadianceFormat;
    d.name = "vct traced diffuse";
    t.diffuse = Image(ctx_, d);
    d.name = "vct traced specular";
    t.specular = Image(ctx_, d);
    d.format = VK_FORMAT_R32G32B32A32_UINT;
    d.name = "vct traced surface";
    t.surface = Image(ctx_, d);
  }
  d.format = kRadianceFormat;
  d.name = "vct diffuse filtered along x";
  filterAlongX_ = Image(ctx_, d);
  d.name = "vct filtered diffuse";
  filteredDiffuse_ = Image(ctx_, d);
}

template <class Push>
void VoxelConeTracing::fillConeParams(Push& p) const {
  const VoxelVolume& v = voxels_.volume();
  p.volume = glm::vec4(v.origin, v.voxelSize);
  p.res = float(res_);
  p.maxDistance = options_.maxDistance * float(res_);
  p.aoDistance = std::max(options_.aoDistance * float(res_), 1e-3f);
  p.coneOffset = options_.coneOffset;
  p.coneStep = options_.coneStep;
  p.cones = options_.diffuseCones;
  p.farNarrowing = options_.farNarrowing;
}

void VoxelConeTracing::recordLeafPass(VkCommandBuffer cmd, const Pipeline& pipeline, const void* push, uint32_t pushBytes,
                                      DescriptorWrites& writes) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  writes.storageBuffer(DYNGI_VCT_INJECT_BINDING_LEAF_LIST, voxels_.leafList().handle())
      .storageImage(DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES, voxels_.voxelAttributes().view())
      .push(ctx_, cmd, pipeline);
  vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, pushBytes, push);
  vkCmdDispatchIndirect(cmd, voxels_.leafList().handle(), 0);  // the list's header: its dispatch
  render::computeWriteBarrier(cmd);
}
static_assert(DYNGI_VCT_INJECT_BINDING_LEAF_LIST == DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST &&
                  DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES == DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES &&
                  DYNGI_VCT_INJECT_BINDING_LEAF_LIST == DYNGI_VCT_EMITTER_BINDING_LEAF_LIST &&
                  DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES == DYNGI_VCT_EMITTER_BINDING_VOXEL_ATTRIBUTES,
              "the passes over leaves share their first two bindings (recordLeafPass)");

uint64_t VoxelConeTracing::recordClearStale(VkCommandBuffer cmd, const StaleVoxels& stale) {
  const bool aniso = options_.anisotropic;
  // Copies and clears run in TRANSFER_DST_OPTIMAL (copies into a GENERAL image are a performance warning
  // of the validation layer), the passes after them in GENERAL again.
  auto toTransfer = [&](Image& img) {
    img.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  };
  auto toGeneral = [&](Image& img) { img.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, kComputeAndTransfer, kReadWrite); };
  if (stale.everywhere) {
    for (Image* img : {&radiance_, &direct_, aniso ? &aniso_ : nullptr, carried_.valid() ? &carried_ : nullptr}) {
      if (!img) continue;
      toTransfer(*img);
      // Radiance level 0 (the isotropic chain is made whole from it; the anisotropic one reads the atlas).
      for (uint32_t m = 0; m < (img == &aniso_ ? aniso_.desc().mips : 1u); ++m) clearLevel(cmd, *img, m);
      toGeneral(*img);
    }
    return uint64_t(res_) * res_ * res_;
  }
  if (stale.boxes.empty()) return 0;
  // The atlas' levels from 2 whole (6 x (res / 8)^3 texels and less; the mips write every occupied one):
  // box by box, their copies of a few texels each cost more.
  if (aniso && aniso_.desc().mips > 2) {
    toTransfer(aniso_);
    for (uint32_t m = 2; m < aniso_.desc().mips; ++m) clearLevel(cmd, aniso_, m);
    toGeneral(aniso_);
  }
  // Level 0, the direct radiance and the atlas' levels 0 and 1: the cells that emptied, within the boxes.
  const uint32_t depth = voxels_.volume().depth();
  std::vector<glm::uvec2> runs;
  for (const VoxelBox& b : stale.boxes) appendRuns(runs, depth, b.min, b.max);
  const size_t leafRuns = runs.size();
  for (uint32_t up = 1; aniso && up <= 2 && up <= depth && up <= aniso_.desc().mips; ++up)
    for (const VoxelBox& b : stale.boxes) appendRuns(runs, depth - up, b.min >> up, b.max >> up);
  std::sort(runs.begin(), runs.end(), [](glm::uvec2 a, glm::uvec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  runs.erase(std::unique(runs.begin(), runs.end()), runs.end());  // boxes overlap
  const VkDeviceSize bytes = runs.size() * sizeof(glm::uvec2);
  if (!staleRuns_.valid() || staleRuns_.size() < bytes) {
    vkDeviceWaitIdle(ctx_.device());  // the last frame may still read the old list
    staleRuns_ = Buffer(ctx_, bytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "vct stale runs");
  }
  staleRuns_.upload(runs.data(), bytes);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, clearStale_.handle());
  DescriptorWrites()
      .storageBuffer(DYNGI_VCT_CLEAR_BINDING_RUNS, staleRuns_.handle())
      .storageBuffer(DYNGI_VCT_CLEAR_BINDING_PREVIOUS_OCCUPANCY, voxels_.previousOccupancy().handle())
      .storageBuffer(DYNGI_VCT_CLEAR_BINDING_OCCUPANCY, voxels_.occupancy().handle())
      .storageImage(DYNGI_VCT_CLEAR_BINDING_RADIANCE, radiance_.mipView(0))
      .storageImage(DYNGI_VCT_CLEAR_BINDING_DIRECT, direct_.view())
      .storageImage(DYNGI_VCT_CLEAR_BINDING_ATLAS, aniso ? aniso_.mipView(0) : radiance_.mipView(0))  // bound either way
      .storageImage(DYNGI_VCT_CLEAR_BINDING_ATLAS_1, aniso && aniso_.desc().mips > 1 ? aniso_.mipView(1) : radiance_.mipView(0))
      .storageImage(DYNGI_VCT_CLEAR_BINDING_CARRIED, carried_.valid() ? carried_.view() : direct_.view())
      .push(ctx_, cmd, clearStale_);
  const gpu::VctClearPush pc{uint32_t(runs.size()), depth, aniso ? std::max(res_ / 2, 1u) : 0u};
  vkCmdPushConstants(cmd, clearStale_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(uint32_t(runs.size()), 64), 1, 1);
  return uint64_t(leafRuns) * 32;
}

void VoxelConeTracing::recordMips(VkCommandBuffer cmd, bool levelZeroIsDirect, RadiancePart part) {
  const bool aniso = options_.anisotropic;
  auto bind = [&](const Pipeline& p, VkImageView source, VkImageView dest, const gpu::VctMipsPush& pc) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
    DescriptorWrites()
        .storageImage(DYNGI_VCT_MIPS_BINDING_SOURCE, source)
        .storageImage(DYNGI_VCT_MIPS_BINDING_DEST, dest)
        .storageImage(DYNGI_VCT_MIPS_BINDING_SEEN, direct_.view())
        .storageBuffer(DYNGI_VCT_MIPS_BINDING_NODE_CELLS, voxels_.nodeCells().handle())
        .storageBuffer(DYNGI_VCT_MIPS_BINDING_LEVELS, voxels_.levels().handle())
        .storageBuffer(DYNGI_VCT_MIPS_BINDING_LEAF_LIST, voxels_.leafList().handle())
        .storageBuffer(DYNGI_VCT_MIPS_BINDING_CHANGED_BOXES, changedBoxes_.handle())
        .push(ctx_, cmd, p);
    vkCmdPushConstants(cmd, p.layout(), kCS, 0, sizeof(pc), &pc);
  };
  if (!aniso) {
    const Pipeline& p = mips(options_.opaqueAxisMips ? MipsVariant::IsotropicOpaqueAxis : MipsVariant::Isotropic);
    for (uint32_t m = 1; m < radiance_.desc().mips; ++m) {
      const uint32_t s = std::max(res_ >> m, 1u);
      bind(p, radiance_.mipView(m - 1), radiance_.mipView(m), {s, 0, 0, 3 * m, part.part, part.parts, part.boxCount});
      vkCmdDispatch(cmd, dispatchGroups(s, 4), dispatchGroups(s, 4), dispatchGroups(s, 4));
      render::computeWriteBarrier(cmd);
    }
    return;
  }
  // The atlas is written only where the SVO has an occupied node, so the rest must be zero: record()
  // clears the texels of nodes that may have emptied first.
  // Level m's texels are 2^(m+1) voxels wide: the cells of SVO level depth - 1 - m. Level 0 from the
  // isotropic level 0 (one source slab), each coarser one from the one below; one invocation per node
  // writes its texel in all six slabs.
  const uint32_t depth = voxels_.volume().depth();
  for (uint32_t m = 0; m < aniso_.desc().mips && m < depth; ++m) {
    const uint32_t slab = std::max((res_ / 2) >> m, 1u), nodeLevel = depth - 1 - m;
    const VkImageView source = m > 0 ? aniso_.mipView(m - 1) : (levelZeroIsDirect ? direct_.view() : radiance_.mipView(0));
    const MipsVariant variant = m > 0 ? MipsVariant::Atlas : levelZeroIsDirect ? MipsVariant::AtlasFromDirect : MipsVariant::AtlasFromLevel0;
    // With changed boxes the atlas' levels from 2 were cleared whole (recordClearStale): written whole.
    const RadiancePart levelPart = part.boxCount > 0 && m >= 2 ? RadiancePart{} : part;
    bind(mips(variant), source, aniso_.mipView(m),
         {slab, m == 0 ? 0u : 2 * slab, nodeLevel, 3 * (depth - nodeLevel), levelPart.part, levelPart.parts, levelPart.boxCount});
    vkCmdDispatchIndirect(cmd, voxels_.levels().handle(), levelDispatchOffset(nodeLevel + 1));  // its nodes' child groups
    render::computeWriteBarrier(cmd);
  }
}

bool VoxelConeTracing::record(render::FrameContext& frame) {
  stats_.injected = false;
  if (!voxels_.hasVolume() || !frame.lights.lights || frame.targets.width == 0) {
    frames_ = 0;  // the voxels this frame's build emptied go uncleared: the next frame clears everything
    return false;
  }
  prepareFrame(frame);
  // The radiance follows the voxels: refreshed when they may update (VoxelScene::updatesThisFrame, each
  // frame unless a GI budget puts the voxel updates off) and whenever the SVO was rebuilt.
  // It may be spread over frames, one part each (planRadianceUpdate): a rebuilt SVO adds the boxes its
  // build changed; the first frame, or one that clears everything, updates every voxel.
  stats_.radianceUpdated = 0.0;
  stats_.carriedUpdated = 0.0;
  if (frames_ == 0 || voxels_.updatesThisFrame() || voxels_.stats().rebuilt) {
    const VolumeChange change = planVolumeChange();
    const RadiancePart part = planRadianceUpdate(change);
    if (carriedWhole_ && carried_.valid()) {  // a light switched or jumped: what the voxels carried is the old light's
      carried_.transition(frame.cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      clearLevel(frame.cmd, carried_, 0);
      carried_.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, kComputeAndTransfer, kReadWrite);
      if (options_.bounceFrames == 0 && !carriesEmitterLight()) carriedWhole_ = false;  // the emitters went: nothing to update
    }
    recordInject(frame, part, change);
    {
      render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "mips");
      recordMips(frame.cmd, /*levelZeroIsDirect=*/!carried_.valid(), part);  // carried light is in level 0, not in the direct radiance
    }
    recordBounces(frame, change);
    stats_.radianceUpdated = 1.0 / double(part.parts);
  }
  const TraceFrame trace = beginTrace(frame);
  recordTrace(frame, trace);
  recordUpsample(frame, trace, recordFilter(frame, trace));
  ++frames_;
  frame.specular = specularSource_;
  return true;
}

// The volumes and trace images for this frame's size and options, every image the passes use in GENERAL.
void VoxelConeTracing::prepareFrame(render::FrameContext& frame) {
  VkCommandBuffer cmd = frame.cmd;
  ensureVolumes(voxels_.volume().resolution);
  ensureTraceTargets(frame.targets.width, frame.targets.height);
  // Back to GENERAL after a read-back (tests); the frames before finished at the renderer's fence, and
  // the passes below order themselves with global barriers.
  for (Image* img : {&radiance_, &aniso_, &direct_, &bounced_, &carried_, &traced_[0].diffuse, &traced_[0].specular, &traced_[0].surface,
                     &traced_[1].diffuse, &traced_[1].specular, &traced_[1].surface, &filterAlongX_, &filteredDiffuse_})
    if (img->valid() && img->layout() != VK_IMAGE_LAYOUT_GENERAL) img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, kComputeAndTransfer, kReadWrite);
  frame.lights.shadowMaps->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  render::RenderTargets& t = frame.targets;
  for (Image* in : {&t.position, &t.normal})
    in->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  for (Image* out : {&t.indirect, &t.specular})
    out->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // A volume moved or resized (VoxelScene::setVolume) makes last frame's radiance belong elsewhere: no
  // blending with it.
  const VoxelVolume& vol = voxels_.volume();
  if (vol.origin != historyOrigin_ || vol.voxelSize != historyVoxelSize_) frames_ = 0;
  historyOrigin_ = vol.origin;
  historyVoxelSize_ = vol.voxelSize;
}

bool VoxelConeTracing::clearsEverything() const {
  uint64_t boxVoxels = 0;
  for (const VoxelBox& b : voxels_.staleBoxes()) boxVoxels += b.voxels();
  return frames_ == 0 || voxels_.staleEverywhere() || boxVoxels * 2 > uint64_t(res_) * res_ * res_;
}

VoxelConeTracing::VolumeChange VoxelConeTracing::planVolumeChange() {
  VolumeChange change;
  change.clearAll = clearsEverything();
  if (!change.clearAll) change.changedBoxes = uploadChangedBoxes();
  return change;
}

VoxelConeTracing::RadiancePart VoxelConeTracing::planRadianceUpdate(const VolumeChange& change) {
  const uint32_t parts = radianceParts();
  // A rebuilt SVO: this frame's part and the boxes where the build changed voxels, whose new voxels would
  // otherwise have no light (and the old ones' emptied mips none) until their part's turn.
  if (parts <= 1 || change.clearAll || !change.changedBoxes) return {};
  return {uint32_t(partFrame_++ % parts), parts, *change.changedBoxes};
}

std::optional<uint32_t> VoxelConeTracing::uploadChangedBoxes() {
  if (!voxels_.stats().rebuilt) return 0u;
  std::vector<glm::uvec4> boxes;
  for (const std::vector<VoxelBox>* list : {&voxels_.staleBoxes(), &voxels_.freshBoxes()})
    for (const VoxelBox& b : *list) {
      boxes.push_back(glm::uvec4(b.min, 0u));
      boxes.push_back(glm::uvec4(b.max, 0u));
    }
  if (boxes.size() > 2 * kMaxChangedBoxes) return std::nullopt;
  if (!boxes.empty()) changedBoxes_.upload(boxes.data(), boxes.size() * sizeof(glm::uvec4));
  return uint32_t(boxes.size() / 2);
}

// "inject": what emptied is cleared, then each occupied voxel's direct light and emission.
void VoxelConeTracing::recordInject(render::FrameContext& frame, RadiancePart part, const VolumeChange& change) {
  VkCommandBuffer cmd = frame.cmd;
  const VoxelVolume& vol = voxels_.volume();
  // Voxels an object left must be empty: the passes below write occupied voxels and texels only. Where
  // the SVO was built this frame, the cells that emptied (vct_clear_stale.comp: in the last build's
  // occupancy, not this one's) are zeroed within the boxes where they may be (VoxelScene::staleBoxes);
  // the first frame, a new volume or boxes holding half of it clear everything. The rest holds the same
  // occupied voxels as before, every one written again below.
  const StaleVoxels stale{change.clearAll, voxels_.stats().rebuilt ? voxels_.staleBoxes() : std::vector<VoxelBox>{}};
  render::ScopedPass scope(ctx_, frame.timer, cmd, "inject");
  stats_.clearedVoxels = recordClearStale(cmd, stale);
  render::computeWriteBarrier(cmd);
  if (carriesEmitterLight()) recordEmitterLight(cmd, change);  // before injection, which adds it
  gpu::VctInjectPush pc{};
  pc.volume = glm::vec4(vol.origin, vol.voxelSize);
  pc.lightCount = frame.lights.count;
  pc.history = frames_ > 0 && options_.temporalBlend > 0.0f ? 1u : 0u;
  pc.temporalBlend = options_.temporalBlend;
  pc.temporalResponse = options_.temporalResponse;
  pc.part = part.part;
  pc.parts = part.parts;
  pc.boxCount = part.boxCount;
  pc.carried = carried_.valid() ? 1u : 0u;
  DescriptorWrites w;
  w.storageBuffer(DYNGI_VCT_INJECT_BINDING_LIGHTS, frame.lights.lights->handle())
      .storageBuffer(DYNGI_VCT_INJECT_BINDING_SHADOW_MATRICES, frame.lights.shadowMatrices->handle())
      .storageImage(DYNGI_VCT_INJECT_BINDING_SHADOW_MAPS, frame.lights.shadowMaps->view())
      .storageImage(DYNGI_VCT_INJECT_BINDING_DIRECT, direct_.view())
      .storageImage(DYNGI_VCT_INJECT_BINDING_RADIANCE, radiance_.mipView(0))
      .storageBuffer(DYNGI_VCT_INJECT_BINDING_CHANGED_BOXES, changedBoxes_.handle())
      .storageImage(DYNGI_VCT_INJECT_BINDING_CARRIED, carried_.valid() ? carried_.view() : direct_.view());  // bound either way
  recordLeafPass(cmd, inject_, &pc, sizeof(pc), w);
  stats_.injected = true;
}

// "bounce": each bounce after the first cone-traces over the occupied voxels, commits to level 0 and
// rebuilds the mips; then this frame's part of the voxels updates the bounce light it carries, which
// next frame's injection adds.
void VoxelConeTracing::recordBounces(render::FrameContext& frame, const VolumeChange& change) {
  VkCommandBuffer cmd = frame.cmd;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "bounce");
  gpu::VctBouncePush pc{};
  fillConeParams(pc);
  // A voxel marches as many cones as a traced pixel (diffuseCones / coneInterleave), each covering its
  // share of the hemisphere, without the far narrowing: no filter brings neighbours' cones in, and so
  // few narrowed cones would lose the light between them.
  pc.cones = (options_.diffuseCones + options_.coneInterleave - 1) / options_.coneInterleave;
  pc.farNarrowing = 0.0f;
  pc.parts = 1;
  for (uint32_t b = 1; b < options_.bounces; ++b) {
    DescriptorWrites w;
    w.storageImage(DYNGI_VCT_BOUNCE_BINDING_DIRECT, direct_.view())
        .sampledImage(DYNGI_VCT_BOUNCE_BINDING_RADIANCE, radiance_.view(), sampler_)
        .sampledImage(DYNGI_VCT_BOUNCE_BINDING_ANISO, anisoView(), sampler_)
        .storageImage(DYNGI_VCT_BOUNCE_BINDING_OUT, bounced_.view())
        .storageBuffer(DYNGI_VCT_BOUNCE_BINDING_CHANGED_BOXES, changedBoxes_.handle())  // bound either way
        .storageBuffer(DYNGI_VCT_BOUNCE_BINDING_PREVIOUS_OCCUPANCY, voxels_.previousOccupancy().handle());
    recordLeafPass(cmd, bounce_[coneVariant().index()].get(), &pc, sizeof(pc), w);
    DescriptorWrites c;
    c.storageImage(DYNGI_VCT_BOUNCE_BINDING_DIRECT, bounced_.view()).storageImage(DYNGI_VCT_BOUNCE_BINDING_OUT, radiance_.mipView(0));
    recordLeafPass(cmd, commit_, &pc, sizeof(pc), c);
    recordMips(cmd, /*levelZeroIsDirect=*/false, RadiancePart{});  // the same occupied set as this frame's first chain; level 0 now has the bounce
  }
  if (!carried_.valid() || options_.bounceFrames == 0) return;
  const RadiancePart part = planCarriedUpdate(change);
  pc.part = part.part;
  pc.parts = part.parts;
  pc.boxCount = part.boxCount;
  // Narrowed far samples, unlike the bounce passes': what a wide footprint brings through a thin wall
  // would be carried again each turn (two-rooms: 5.5 percent of the doorway's light leaks into the closed
  // room without, 3.4 with), and the light lost between the cones stays under 3 percent.
  pc.farNarrowing = options_.farNarrowing;
  DescriptorWrites w;
  w.storageImage(DYNGI_VCT_BOUNCE_BINDING_DIRECT, direct_.view())  // unread
      .sampledImage(DYNGI_VCT_BOUNCE_BINDING_RADIANCE, radiance_.view(), sampler_)
      .sampledImage(DYNGI_VCT_BOUNCE_BINDING_ANISO, anisoView(), sampler_)
      .storageImage(DYNGI_VCT_BOUNCE_BINDING_OUT, carried_.view())
      .storageBuffer(DYNGI_VCT_BOUNCE_BINDING_CHANGED_BOXES, changedBoxes_.handle())
      .storageBuffer(DYNGI_VCT_BOUNCE_BINDING_PREVIOUS_OCCUPANCY, voxels_.previousOccupancy().handle());
  recordLeafPass(cmd, carry_[coneVariant().index()].get(), &pc, sizeof(pc), w);
}

// Every voxel after a refresh (a light switched or jumped, other emitter points), when the volume was
// cleared (the first frame, a move) or too many boxes changed, unless a GI budget spreads one-off work;
// else this frame's part and the voxels this frame's SVO build added (in the boxes where it changed
// voxels), so a moved object carries its light from its first frame.
VoxelConeTracing::RadiancePart VoxelConeTracing::planCarriedUpdate(const VolumeChange& change) {
  const std::optional<uint32_t> boxes = change.changedBoxes;
  const bool whole = (carriedWhole_ || change.clearAll || !boxes) && !spreadWithoutHistory_;
  carriedWhole_ = false;
  RadiancePart p;
  p.parts = whole ? 1u : carriedFrames() * budgetCarriedSlowdown_;
  p.part = whole ? 0u : uint32_t(carriedFrame_++ % p.parts);
  p.boxCount = whole || budgetCarriedSlowdown_ > 1 || !boxes ? 0u : *boxes;  // a budget's slowdown leaves new voxels to their turn
  stats_.carriedUpdated = 1.0 / double(p.parts);
  return p;
}

void VoxelConeTracing::setEmitterPoints(const std::vector<gpu::VctEmitterPoint>& points) {
  static_assert(sizeof(gpu::VctEmitterPoint) == 3 * sizeof(glm::vec4));
  std::vector<glm::vec4> packed(3 * points.size());
  if (!points.empty()) std::memcpy(packed.data(), points.data(), points.size() * sizeof(gpu::VctEmitterPoint));
  emittersSeen_ = emittersSeen_ || !points.empty();
  if (packed == lastEmitterPoints_) return;
  if (!points.empty()) emitterPoints_.upload(points.data(), points.size() * sizeof(gpu::VctEmitterPoint));
  lastEmitterPoints_ = std::move(packed);
  carriedWhole_ = true;
}

// Part of "inject": the emitters' light on this frame's part of the voxels, into the carried image. It
// depends on the geometry and the points alone: a still scene keeps it, and after an SVO build one turn
// of the parts brings every voxel up to date (an occluder's shadow moved, an albedo edited).
void VoxelConeTracing::recordEmitterLight(VkCommandBuffer cmd, const VolumeChange& change) {
  const bool restart = voxels_.stats().rebuilt || change.clearAll || carriedWhole_;
  if (!restart && emitterFramesLeft_ == 0) return;
  const RadiancePart part = planCarriedUpdate(change);
  emitterFramesLeft_ = part.parts == 1 ? 0u : restart ? part.parts - 1 : emitterFramesLeft_ - 1;
  const VoxelVolume& vol = voxels_.volume();
  gpu::VctEmitterPush pc{};
  pc.volume = glm::vec4(vol.origin, vol.voxelSize);
  pc.res = float(vol.resolution);
  pc.svoDepth = vol.depth();
  pc.samples = options_.emitterSamples;
  pc.part = part.part;
  pc.parts = part.parts;
  pc.boxCount = part.boxCount;
  DescriptorWrites w;
  w.storageImage(DYNGI_VCT_EMITTER_BINDING_OUT, carried_.view())
      .storageBuffer(DYNGI_VCT_EMITTER_BINDING_CHANGED_BOXES, changedBoxes_.handle())
      .storageBuffer(DYNGI_VCT_EMITTER_BINDING_PREVIOUS_OCCUPANCY, voxels_.previousOccupancy().handle())
      .storageBuffer(DYNGI_VCT_EMITTER_BINDING_SVO_NODES, voxels_.nodes().handle())
      .storageBuffer(DYNGI_VCT_EMITTER_BINDING_POINTS, emitterPoints_.handle());
  recordLeafPass(cmd, emitterLight_, &pc, sizeof(pc), w);
}

VoxelConeTracing::TraceFrame VoxelConeTracing::beginTrace(const render::FrameContext& frame) {
  TraceFrame trace;
  trace.scale = traceScale();
  // Nothing to carry over (first frame, new trace targets, a light switched): every pixel is traced,
  // unless a budget spreads that frame too (the missing pixels upsampled from this frame's).
  trace.frames = traceHistory_ || spreadWithoutHistory_ ? options_.traceFrames : 1u;
  trace.phase = uint32_t(traceFrame_ % trace.frames);
  trace.quarterWithoutHistory = !traceHistory_ && trace.frames == 4;
  ++traceFrame_;
  trace.lastFrame = &traced_[tracedCurrent_];
  tracedCurrent_ ^= 1u;
  trace.current = &traced_[tracedCurrent_];
  stats_.tracedFraction = 1.0 / trace.frames;
  stats_.traceWidth = trace.current->diffuse.desc().width;
  stats_.traceHeight = trace.current->diffuse.desc().height;
  // Without a draw smoother than specularConeBelow (a roughness texture may make any pixel so), no
  // pixel marches a specular cone: the variant without its code, which lavapipe would run masked.
  trace.glossy = options_.specular && std::any_of(frame.snapshot.draws.begin(), frame.snapshot.draws.end(), [&](const render::DrawItem& d) {
                   const scene::Material& m = frame.snapshot.materialOf(d);
                   return m.roughness < options_.specularConeBelow || m.metallicRoughnessTexture != scene::kNoTexture;
                 });
  stats_.specularCones = trace.glossy;
  // The specular image is written where some pixel's specular light is a cone's, or the debug view
  // shows it; else the lighting takes the diffuse light as the specular (SpecularSource::Indirect).
  specularSource_ = !options_.specular                                     ? render::SpecularSource::None
                    : trace.glossy || options_.view == VctView::Specular ? render::SpecularSource::Target
                                                                           : render::SpecularSource::Indirect;
  return trace;
}

// "trace": the cones of this frame's traced pixels, then the rest reprojected from last frame.
void VoxelConeTracing::recordTrace(render::FrameContext& frame, const TraceFrame& trace) {
  VkCommandBuffer cmd = frame.cmd;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "trace");
  render::RenderTargets& t = frame.targets;
  const Pipeline& p = trace_[TraceVariant{options_.anisotropic, trace.glossy, unitStep() == 1}.index()].get();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VCT_TRACE_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_VCT_TRACE_BINDING_G_POSITION, t.position.view())
      .storageImage(DYNGI_VCT_TRACE_BINDING_G_NORMAL, t.normal.view())
      .sampledImage(DYNGI_VCT_TRACE_BINDING_RADIANCE, radiance_.view(), sampler_)
      .sampledImage(DYNGI_VCT_TRACE_BINDING_ANISO, anisoView(), sampler_)
      .storageImage(DYNGI_VCT_TRACE_BINDING_OUT_DIFFUSE, trace.current->diffuse.view())
      .storageImage(DYNGI_VCT_TRACE_BINDING_OUT_SPECULAR, trace.current->specular.view())
      .push(ctx_, cmd, p);
  gpu::VctTracePush pc{};
  fillConeParams(pc);
  pc.traceScale = trace.scale;
  pc.specular = trace.glossy ? 1u : 0u;
  pc.specularConeBelow = options_.specularConeBelow;
  pc.turnCones = options_.diffuseFilterRadius > 0 ? 1u : 0u;
  pc.traceFrames = trace.frames;
  pc.tracePhase = trace.phase;
  pc.coneInterleave = options_.coneInterleave;
  pc.coneRowShift = trace.quarterWithoutHistory ? 1u : 0u;
  vkCmdPushConstants(cmd, p.layout(), kCS, 0, sizeof(pc), &pc);
  // With traceFrames > 1: the 2 x 2 lattice's cells, once per offset traced this frame (vct_trace_phase.glsl).
  const uint32_t step = trace.frames > 1 ? 2 : 1;
  vkCmdDispatch(cmd, dispatchGroups((stats_.traceWidth + step - 1) / step, 8), dispatchGroups((stats_.traceHeight + step - 1) / step, 8),
                trace.frames > 1 ? 4 / trace.frames : 1);
  render::computeWriteBarrier(cmd);
  recordReproject(frame, trace);
  traceHistory_ = true;
  previousViewProj_ = frame.uniforms.viewProj;
}

// The pixels not traced this frame, from last frame's, and every traced pixel's surface record (for the
// filter, the upsample and next frame; the only work when every pixel is traced).
void VoxelConeTracing::recordReproject(render::FrameContext& frame, const TraceFrame& trace) {
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reproject_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VCT_REPROJECT_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_G_POSITION, t.position.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_G_NORMAL, t.normal.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_DIFFUSE, trace.lastFrame->diffuse.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SPECULAR, trace.lastFrame->specular.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SURFACE, trace.lastFrame->surface.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_OUT_DIFFUSE, trace.current->diffuse.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_OUT_SPECULAR, trace.current->specular.view())
      .storageImage(DYNGI_VCT_REPROJECT_BINDING_OUT_SURFACE, trace.current->surface.view())
      .push(ctx_, cmd, reproject_);
  gpu::VctReprojectPush rp{};
  rp.previousViewProj = previousViewProj_;
  rp.traceScale = trace.scale;
  rp.traceFrames = trace.frames;
  rp.tracePhase = trace.phase;
  rp.history = traceHistory_ ? 1u : 0u;
  // Twice the frames a still pixel waits for its turn: under motion a value can be carried from pixel to
  // pixel without ever coming up for tracing.
  rp.maxAge = 2 * trace.frames;
  vkCmdPushConstants(cmd, reproject_.layout(), kCS, 0, sizeof(rp), &rp);
  vkCmdDispatch(cmd, dispatchGroups(stats_.traceWidth, 8), dispatchGroups(stats_.traceHeight, 8), 1);
  render::computeWriteBarrier(cmd);
}

// "filter" (diffuseFilterRadius > 0): the traced diffuse light along x, then y. Returns what the
// upsample reads.
const Image& VoxelConeTracing::recordFilter(render::FrameContext& frame, const TraceFrame& trace) {
  if (options_.diffuseFilterRadius == 0) return trace.current->diffuse;
  VkCommandBuffer cmd = frame.cmd;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "filter");
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, filter_.handle());
  // Along x into filterAlongX_, then along y into filteredDiffuse_, which the upsample reads.
  const Image* passes[2][2] = {{&trace.current->diffuse, &filterAlongX_}, {&filterAlongX_, &filteredDiffuse_}};
  for (int axis = 0; axis < 2; ++axis) {
    DescriptorWrites()
        .uniformBuffer(DYNGI_VCT_FILTER_BINDING_FRAME, frame.frameUniforms.handle())
        .storageImage(DYNGI_VCT_FILTER_BINDING_SURFACE, trace.current->surface.view())
        .storageImage(DYNGI_VCT_FILTER_BINDING_IN, passes[axis][0]->view())
        .storageImage(DYNGI_VCT_FILTER_BINDING_OUT, passes[axis][1]->view())
        .push(ctx_, cmd, filter_);
    const int radius = int(options_.diffuseFilterRadius) * (trace.quarterWithoutHistory ? 2 : 1);
    const gpu::VctFilterPush pc{trace.scale, radius, axis == 0 ? 1 : 0, axis == 1 ? 1 : 0};
    vkCmdPushConstants(cmd, filter_.layout(), kCS, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, dispatchGroups(stats_.traceWidth, 8), dispatchGroups(stats_.traceHeight, 8), 1);
    render::computeWriteBarrier(cmd);
  }
  return filteredDiffuse_;
}

// "upsample": the traced light to every pixel -> targets.indirect and targets.specular.
void VoxelConeTracing::recordUpsample(render::FrameContext& frame, const TraceFrame& trace, const Image& diffuse) {
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  render::ScopedPass scope(ctx_, frame.timer, cmd, "upsample");
  const Pipeline& up = upsample_[specularSource_ == render::SpecularSource::Target ? 1 : 0].get();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, up.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VCT_UPSAMPLE_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_G_POSITION, t.position.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_G_NORMAL, t.normal.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_LOW_DIFFUSE, diffuse.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_LOW_SPECULAR, trace.current->specular.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_LOW_SURFACE, trace.current->surface.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_OUT_DIFFUSE, t.indirect.view())
      .storageImage(DYNGI_VCT_UPSAMPLE_BINDING_OUT_SPECULAR, t.specular.view())
      .push(ctx_, cmd, up);
  const gpu::VctUpsamplePush pc{trace.scale, options_.specularConeBelow};
  vkCmdPushConstants(cmd, up.layout(), kCS, 0, sizeof(pc), &pc);
  // One invocation per block of scale x scale pixels sharing their traced neighbours: a block left of
  // and above the first traced pixel, then one per traced pixel.
  vkCmdDispatch(cmd, dispatchGroups(stats_.traceWidth + 1, 8), dispatchGroups(stats_.traceHeight + 1, 8), 1);
  render::computeWriteBarrier(cmd);
}

void VoxelConeTracing::recordAfterLighting(render::FrameContext& frame) {
  if (options_.view == VctView::Final || !radiance_.valid()) return;
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& t = frame.targets;
  t.hdr.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const bool aniso = options_.anisotropic;
  const Pipeline& p = debug_[aniso ? 1 : 0].get();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_VCT_DEBUG_BINDING_FRAME, frame.frameUniforms.handle())
      .sampledImage(DYNGI_VCT_DEBUG_BINDING_RADIANCE, radiance_.view(), sampler_)
      .sampledImage(DYNGI_VCT_DEBUG_BINDING_ANISO, aniso ? aniso_.view() : radiance_.view(), sampler_)
      .storageImage(DYNGI_VCT_DEBUG_BINDING_INDIRECT, t.indirect.view())
      .storageImage(DYNGI_VCT_DEBUG_BINDING_SPECULAR, t.specular.view())
      .storageImage(DYNGI_VCT_DEBUG_BINDING_OUT_HDR, t.hdr.view())
      .push(ctx_, cmd, p);
  gpu::VctDebugPush pc{};
  fillConeParams(pc);
  pc.mode = uint32_t(options_.view) - uint32_t(VctView::Radiance);
  pc.mip = float(std::min(options_.viewMip, radiance_.desc().mips - 1));
  vkCmdPushConstants(cmd, p.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(t.width, 8), dispatchGroups(t.height, 8), 1);
  render::computeWriteBarrier(cmd);
}

std::vector<glm::vec4> VoxelConeTracing::probeCones(const std::vector<std::pair<glm::vec3, glm::vec3>>& rays, float tanHalf) {
  std::vector<glm::vec4> results(rays.size());
  if (rays.empty() || !radiance_.valid()) return results;
  std::vector<glm::vec4> packed;
  for (const auto& [o, d] : rays) packed.push_back(glm::vec4(o, 0.0f)), packed.push_back(glm::vec4(d, 0.0f));
  Buffer rayBuf(ctx_, packed.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "vct probe rays");
  rayBuf.upload(packed.data(), packed.size() * sizeof(glm::vec4));
  Buffer out(ctx_, rays.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "vct probe results");
  const bool aniso = options_.anisotropic;
  const Pipeline& p = probe_[coneVariant().index()].get();  // the trace's variant
  ctx_.immediate([&](VkCommandBuffer cmd) {
    for (Image* img : {&radiance_, &aniso_})
      if (img->valid()) img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
    DescriptorWrites()
        .storageBuffer(DYNGI_VCT_PROBE_BINDING_RAYS, rayBuf.handle())
        .sampledImage(DYNGI_VCT_PROBE_BINDING_RADIANCE, radiance_.view(), sampler_)
        .sampledImage(DYNGI_VCT_PROBE_BINDING_ANISO, aniso ? aniso_.view() : radiance_.view(), sampler_)
        .storageBuffer(DYNGI_VCT_PROBE_BINDING_RESULTS, out.handle())
        .push(ctx_, cmd, p);
    gpu::VctProbePush pc{};
    fillConeParams(pc);
    pc.count = uint32_t(rays.size());
    pc.tanHalf = tanHalf;
    vkCmdPushConstants(cmd, p.layout(), kCS, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, dispatchGroups(uint32_t(rays.size()), 64), 1, 1);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                          VK_ACCESS_2_HOST_READ_BIT);
  });
  out.invalidateForRead();
  std::memcpy(results.data(), out.mapped(), results.size() * sizeof(glm::vec4));
  return results;
}

}  // namespace dyngi::gi
