#include "dyngi/gi/voxel_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "dyngi/engine/render/draw_pass.h"
#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/scene/animation.h"
#include "camera_focus.h"
#include "voxel/shaders/voxel_shared.h"
#include "voxel/svo_builder.h"
#include "voxel/voxel_debug_pass.h"
#include "spirv/voxelize.frag.spv.h"
#include "spirv/voxelize.geom.spv.h"
#include "spirv/voxelize.vert.spv.h"
#include "spirv/voxelize_tangent.vert.spv.h"
#include "spirv/voxelize_small.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

const OptionTable<VoxelSettings>& VoxelSettings::table() {
  static const OptionTable<VoxelSettings> t = OptionTable<VoxelSettings>("voxel").add(
      DYNGI_OPTION(VoxelSettings, resolution), "voxel volume resolution (the SVO's finest level)", 64, 512, /*powerOfTwo=*/true)
      .add(DYNGI_OPTION(VoxelSettings, reach), "metres around the camera the voxel volume covers when the scene is wider (0: the whole scene)", 0, 100000);
  return t;
}

namespace {
// Spans (first, count) merged where they overlap or touch, in order.
std::vector<std::pair<uint64_t, uint64_t>> coalesceSpans(std::vector<std::pair<uint64_t, uint64_t>> spans) {
  std::sort(spans.begin(), spans.end());
  std::vector<std::pair<uint64_t, uint64_t>> out;
  for (const auto& [first, count] : spans) {
    if (count == 0) continue;
    if (!out.empty() && first <= out.back().first + out.back().second)
      out.back().second = std::max(out.back().second, first + count - out.back().first);
    else
      out.push_back({first, count});
  }
  return out;
}
constexpr uint32_t kAttributeInts = DYNGI_LEAF_ATTRIBUTE_INTS;  // ints per leaf in the attribute buffer
// The leaf slots the attributes start with: two per fragment slot, at most 2^20 (32 MB) and at most what
// the voxel boxes allow (occupancyBound), and at least what the last build's leaf level needs (what
// frameFinished grows them to after a build that needed more). Dense fragments (many small instances)
// would otherwise reserve far more leaves than the SVO has.
constexpr uint64_t kAttributeSlotsPerFragment = 2;
constexpr uint64_t kAttributeLeavesAtFirst = 1u << 20;
uint64_t startingAttributeLeaves(uint64_t fragmentSlots, uint64_t lastLeafSlots, uint64_t boxesBound = UINT64_MAX) {
  return std::max(std::min({kAttributeSlotsPerFragment * fragmentSlots, kAttributeLeavesAtFirst, boxesBound}), lastLeafSlots + lastLeafSlots / 2);
}
}  // namespace

VoxelScene::VoxelScene(render::VulkanContext& ctx, const VoxelSettings& settings) : ctx_(ctx), settings_(settings) {
  uint32_t r = settings.resolution;
  if (r < 8 || r > 1024 || (r & (r - 1)) != 0)
    throw std::invalid_argument("voxel resolution must be a power of two in 8..1024, got " + std::to_string(r));

  debugPass_ = std::make_unique<VoxelDebugPass>(ctx);
  svo_ = std::make_unique<SvoBuilder>(ctx, settings_.resolution, settings_.maxNodeGroups);
  reallocateFragments(1u << 16, {});
}

VoxelScene::~VoxelScene() = default;

const render::Buffer& VoxelScene::nodes() const { return svo_->nodes(); }
const render::Buffer& VoxelScene::levels() const { return svo_->levels(); }
const render::Buffer& VoxelScene::nodeCells() const { return svo_->nodeCells(); }
const render::Buffer& VoxelScene::leafList() const { return svo_->leafList(); }
const render::Buffer& VoxelScene::occupancy() const { return svo_->occupancy(); }
const render::Buffer& VoxelScene::previousOccupancy() const { return svo_->previousOccupancy(); }

void VoxelScene::setDebugView(VoxelDebugView v) {
  settings_.debugView = v;
  if (v == VoxelDebugView::Voxels) enableLeafAttributes();  // the view colours voxels by albedo
}

void VoxelScene::enableLeafAttributes() {
  if (!settings_.leafAttributes) {
    settings_.leafAttributes = true;
    allocateAttributes(startingAttributeLeaves(stats_.fragmentCapacity, stats_.leafSlots));
    storageMoved_ = true;  // build them
  }
}

void VoxelScene::setVolume(const VoxelVolume& v) {
  volume_ = v;
  volume_.resolution = settings_.resolution;
  haveVolume_ = true;
  volumeFixed_ = true;
  stats_.windowed = false;
  allDirty_ = true;
}

void VoxelScene::placeVolume(const render::RenderSnapshot& snapshot) {
  if (volumeFixed_) return;
  const CameraFocus focus = cameraFocus(snapshot, settings_.reach, kWindowStep * settings_.reach);
  if (focus.wholeScene) {
    // The scene's bounds, decided once: an object that moves past them does not re-voxelize everything.
    if (haveVolume_ && !stats_.windowed) return;
    volume_ = VoxelVolume::around(snapshot.sceneBounds, settings_.resolution, settings_.padding);
  } else {
    VoxelVolume window = VoxelVolume::around(focus.bounds, settings_.resolution, settings_.padding);
    // On one grid of that voxel size (every window has the same): where two windows overlap they hold the
    // same voxels, so a move changes nothing the camera sees near it but what the window uncovers. The grid
    // is half a voxel off the world's origin: a ground at height 0 on a side between two layers of voxels
    // would touch both (contact counts) and block segments over it as a ground twice as thick.
    window.origin = (glm::floor(window.origin / window.voxelSize) + 0.5f) * window.voxelSize;
    if (haveVolume_ && stats_.windowed && window.origin == volume_.origin && window.voxelSize == volume_.voxelSize) return;
    if (haveVolume_) ++stats_.volumeMoves;
    volume_ = window;
  }
  stats_.windowed = !focus.wholeScene;
  haveVolume_ = true;
  allDirty_ = true;
}

void VoxelScene::ensureCapacity(uint64_t slots) {
  if (fragments_.valid() && fragments_.size() >= slots * 16) return;
  std::vector<SlotCopy> keep;
  if (fragments_.valid() && ranges_.highWater() > 0) keep.push_back({0, 0, ranges_.highWater()});
  // Headroom for the next growth once something is stored; the first allocation holds what was asked.
  const uint64_t headroom = keep.empty() ? 0 : slots / 2;
  reallocateFragments(std::max<uint64_t>(slots + headroom, 1u << 16), keep);
}

void VoxelScene::reallocateFragments(uint64_t slots, const std::vector<SlotCopy>& keepSlots) {
  std::vector<VkBufferCopy> keep;
  for (const SlotCopy& c : keepSlots) keep.push_back({c.from * 16, c.to * 16, c.count * 16});
  vkDeviceWaitIdle(ctx_.device());
  Buffer fresh(ctx_, slots * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "voxel fragments");
  ctx_.immediate([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, fresh.handle(), 0, VK_WHOLE_SIZE, DYNGI_VOXEL_EMPTY);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (!keep.empty()) vkCmdCopyBuffer(cmd, fragments_.handle(), fresh.handle(), uint32_t(keep.size()), keep.data());
  });
  fragments_ = std::move(fresh);
  stats_.fragmentCapacity = slots;
  allocateAttributes(settings_.leafAttributes ? startingAttributeLeaves(slots, stats_.leafSlots, occupancyBound().leafSlots) : 0);
  storageMoved_ = true;
}

// The SVO has a group of eight nodes under every occupied cell of levels 0..depth-1, and every voxel
// lies in its entity's box: the cells of twice the voxel's side that the boxes touch, and their parents
// up to the root, bound the groups, and eight leaf slots per such half-resolution cell bound the leaf
// slots. Dense small instances (a field of 200,000 quads: 1.3 million fragments in 65,000 slots) would
// otherwise start the leaf attributes at the 2^20 cap and the node pool at the full tree. Before the
// first voxelization, or past kMaxCells of work, no bound is given.
VoxelScene::OccupancyBound VoxelScene::occupancyBound() const {
  constexpr uint64_t kMaxCells = 1u << 24;
  uint32_t side = std::max(volume_.resolution / 2, 1u);
  if (voxelBoxes_.empty() || uint64_t(side) * side * side > kMaxCells) return {};  // no boxes yet: unknown
  std::vector<uint64_t> seen((uint64_t(side) * side * side + 63) / 64, 0);
  uint64_t cells = 0, visited = 0;
  for (const auto& [e, box] : voxelBoxes_) {
    const glm::uvec3 lo = box.min / 2u, hi = glm::min(box.max / 2u, glm::uvec3(side - 1));
    visited += uint64_t(hi.x - lo.x + 1) * (hi.y - lo.y + 1) * (hi.z - lo.z + 1);
    if (visited > kMaxCells) return {};
    for (uint32_t z = lo.z; z <= hi.z; ++z)
      for (uint32_t y = lo.y; y <= hi.y; ++y)
        for (uint32_t x = lo.x; x <= hi.x; ++x) {
          const uint64_t i = (uint64_t(z) * side + y) * side + x;
          if (!(seen[i / 64] >> (i % 64) & 1u)) seen[i / 64] |= uint64_t(1) << (i % 64), ++cells;
        }
  }
  OccupancyBound bound{8 * cells, cells};
  for (; side > 1; side /= 2) {  // each level's touched cells are the parents of the level below's
    const uint32_t half = side / 2;
    std::vector<uint64_t> parents((uint64_t(half) * half * half + 63) / 64, 0);
    for (size_t w = 0; w < seen.size(); ++w)
      for (uint64_t bits = seen[w]; bits != 0; bits &= bits - 1) {
        const uint64_t i = w * 64 + uint64_t(std::countr_zero(bits));
        const uint64_t x = i % side, y = i / side % side, z = i / (uint64_t(side) * side);
        const uint64_t j = (z / 2 * half + y / 2) * half + x / 2;
        if (!(parents[j / 64] >> (j % 64) & 1u)) parents[j / 64] |= uint64_t(1) << (j % 64), ++bound.nodeGroups;
      }
    seen.swap(parents);
  }
  return bound;
}

void VoxelScene::allocateAttributes(uint64_t leafSlots) {
  vkDeviceWaitIdle(ctx_.device());
  attributes_ = Buffer(ctx_, std::max<uint64_t>(leafSlots * kAttributeInts * 4, 16), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       MemoryUsage::GpuOnly, "voxel leaf sums");
  attributeLeaves_ = leafSlots;
  ctx_.immediate([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, attributes_.handle(), 0, VK_WHOLE_SIZE, 0); });  // builds leave it zero
  // The voxel attributes: one texel (bound, never read) until the leaf attributes are on.
  const uint32_t side = leafSlots > 0 ? settings_.resolution : 1u;
  if (!voxelAttributes_.valid() || voxelAttributes_.desc().width != side) {
    render::ImageDesc d;
    d.width = d.height = d.depth = side;
    d.format = VK_FORMAT_R32G32B32A32_UINT;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.viewType = VK_IMAGE_VIEW_TYPE_3D;
    d.name = "voxel attributes";
    voxelAttributes_ = Image(ctx_, d);
    ctx_.immediate([&](VkCommandBuffer cmd) {
      voxelAttributes_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      const VkClearColorValue zero{};
      const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, voxelAttributes_.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    });
    svo_->invalidateStaticOccupancy();  // the next build fills it
  }
}

void VoxelScene::compactFragments() {
  const std::vector<SlotCopy> keep = ranges_.compact();
  const uint64_t next = ranges_.highWater();
  reallocateFragments(std::max<uint64_t>(next + next / 4, FragmentRanges::kMinCompactSlots), keep);
}

ecs::EntitySet VoxelScene::deferredByCap(const render::RenderSnapshot& snapshot, const glm::mat4& toVoxel) const {
  const uint64_t cap = voxelizeCap_ > 0 ? voxelizeCap_
                       : spreadVoxelization_ ? std::max<uint64_t>(kMinSpreadFragments, ranges_.storedFragments() / 4)
                                             : 0;
  if (cap == 0) return {};
  ecs::EntityMap<uint64_t> estimates;  // of the dirty entities drawn this frame
  for (const auto& d : snapshot.draws)
    if (dirty_.count(d.entity)) estimates[d.entity] += FragmentRanges::estimateFragments(snapshot.assets->mesh(d.mesh), toVoxel * d.model, volume_.resolution);
  std::vector<std::pair<uint64_t, ecs::Entity>> waiting;  // (changed since, entity): the longest waiting first
  for (const auto& [e, estimate] : estimates) {
    const auto since = dirtySince_.find(e);
    waiting.push_back({since != dirtySince_.end() ? since->second : frameIndex_, e});
  }
  std::sort(waiting.begin(), waiting.end());
  ecs::EntitySet deferred;
  uint64_t taken = 0;
  for (const auto& [since, e] : waiting) {
    const uint64_t estimate = estimates[e];
    if (taken > 0 && taken + estimate > cap) deferred.insert(e);
    else taken += estimate;
  }
  return deferred;
}

void VoxelScene::prepare(render::VulkanContext&, const render::RenderSnapshot& snapshot) {
  drawsToVoxelize_.clear();
  rasterDraws_.clear();
  computeDraws_.clear();
  rangesToEmpty_.clear();
  voxelizedThisFrame_.clear();
  staleBoxes_.clear();
  freshBoxes_.clear();
  staleEverywhere_ = false;
  rebuildSvo_ = false;
  stats_.rebuilt = false;
  stats_.entitiesVoxelized = 0;
  stats_.entitiesDeferred = 0;
  if (!snapshot.assets) return;
  ++frameIndex_;
  placeVolume(snapshot);
  updatesThisFrame_ = allDirty_ || updateInterval_ <= 1 || frameIndex_ % updateInterval_ == 0;
  if (!updatesThisFrame_) return;  // dirty_ and removed_ keep what changed for the next update
  const glm::mat4 toVoxel = volume_.worldToVoxelMatrix();

  // Entities that disappeared from the draw list count as removed (a full update forgets them all).
  if (!allDirty_ && !ranges_.all().empty()) {
    ecs::EntitySet present;
    present.reserve(snapshot.draws.size());
    for (const auto& d : snapshot.draws) present.insert(d.entity);
    for (const auto& [e, r] : ranges_.all())
      if (!present.count(e)) removed_.insert(e);
  }

  // Compact when the ranges hold more than twice what they need (counts from the last frame): after
  // the first frame, and again as moved entities leave holes.
  if (!allDirty_ && ranges_.wantsCompaction()) compactFragments();
  const bool wholeVolume = allDirty_;
  if (allDirty_) {
    svo_->invalidateStaticOccupancy();
    ranges_.clear();
    ranges_.reserve(snapshot.draws.size());  // filled below: no copies while it grows
    rangesToEmpty_.clear();
    voxelBoxes_.clear();
    voxelBoxes_.reserve(snapshot.draws.size());
    emittingEntities_.clear();
    staleEverywhere_ = true;
    allDirty_ = false;
    rebuildSvo_ = true;
  }
  std::vector<ecs::Entity> removedNow;
  for (ecs::Entity e : removed_) {
    const std::optional<Range> r = ranges_.remove(e);
    if (!r) continue;
    removedNow.push_back(e);
    rangesToEmpty_.push_back(*r);
    emittingEntities_.erase(e);
    if (const auto box = voxelBoxes_.find(e); box != voxelBoxes_.end()) {
      staleBoxes_.push_back(box->second);
      voxelBoxes_.erase(box);
    }
    rebuildSvo_ = true;
  }
  removed_.clear();
  drawsToVoxelize_.clear();
  const ecs::EntitySet deferred = wholeVolume ? ecs::EntitySet{} : deferredByCap(snapshot, toVoxel);
  uint64_t newHighWater = ranges_.highWater();
  // Each re-voxelized entity's old box is stale; its new one is what it covers now (a voxel of margin:
  // the voxelization is conservative). A snapshot has one draw per entity.
  const float top = float(volume_.resolution - 1);
  for (size_t i = 0; i < snapshot.draws.size(); ++i) {
    const auto& d = snapshot.draws[i];
    if (!(wholeVolume || dirty_.count(d.entity)) || deferred.count(d.entity)) continue;
    if (glm::any(glm::greaterThan(snapshot.materialOf(d).emissive, glm::vec3(0.0f)))) emittingEntities_.insert(d.entity);
    else emittingEntities_.erase(d.entity);
    if (const auto old = voxelBoxes_.find(d.entity); old != voxelBoxes_.end()) {
      if (!staleEverywhere_) staleBoxes_.push_back(old->second);
      voxelBoxes_.erase(old);
    }
    const scene::Aabb bounds = snapshot.assets->mesh(d.mesh).bounds.transformed(toVoxel * d.model);
    const glm::vec3 lo = glm::floor(bounds.min) - 1.0f, hi = glm::floor(bounds.max) + 1.0f;
    if (bounds.valid() && !glm::any(glm::greaterThan(lo, glm::vec3(top))) && !glm::any(glm::lessThan(hi, glm::vec3(0.0f)))) {
      const VoxelBox box{glm::uvec3(glm::clamp(lo, 0.0f, top)), glm::uvec3(glm::clamp(hi, 0.0f, top))};
      voxelBoxes_[d.entity] = box;
      if (!staleEverywhere_) freshBoxes_.push_back(box);
    }
    const FragmentRanges::Estimate estimate = FragmentRanges::estimate(snapshot.assets->mesh(d.mesh), toVoxel * d.model, volume_.resolution);
    // Committed at once: the growth below keeps the slots under the last frame's high water, which
    // a new range (planned above it) never overlaps.
    ranges_.commit(d.entity, ranges_.plan(d.entity, estimate.fragments, newHighWater, rangesToEmpty_), frameIndex_);
    voxelizedThisFrame_.push_back(d.entity);
    drawsToVoxelize_.push_back(i);
    (voxelizesByCompute(snapshot, d, estimate) ? computeDraws_ : rasterDraws_).push_back(i);
  }
  ensureCapacity(newHighWater);  // grows by copying: nothing already voxelized is lost
  ranges_.setHighWater(newHighWater);
  dirty_ = deferred;
  stats_.entitiesDeferred = uint32_t(deferred.size());
  for (auto it = dirtySince_.begin(); it != dirtySince_.end();) it = deferred.count(it->first) ? std::next(it) : dirtySince_.erase(it);
  if (!drawsToVoxelize_.empty() || storageMoved_) rebuildSvo_ = true;
  storageMoved_ = false;
  uint64_t countersBytes = uint64_t(std::max(ranges_.counterCount(), 1u)) * 4;
  if (!counters_.valid() || counters_.size() < countersBytes) {
    vkDeviceWaitIdle(ctx_.device());
    Buffer grown(ctx_, std::max<uint64_t>(countersBytes * 2, 1024), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "voxel counters");
    if (counters_.valid()) std::memcpy(grown.mapped(), counters_.mapped(), counters_.size());
    counters_ = std::move(grown);
  }
  stats_.entitiesVoxelized = uint32_t(drawsToVoxelize_.size());
  if (!drawsToVoxelize_.empty()) stats_.drawsComputeVoxelized = uint32_t(computeDraws_.size());
  if (rebuildSvo_ && !svo_->built()) svo_->fitFirstPool(occupancyBound().nodeGroups);
  if (rebuildSvo_) svo_->plan(ranges_, frameIndex_, voxelizedThisFrame_, removedNow, stats_);
}

QualityKnob VoxelScene::updateFractionKnob() {
  return {"voxel_update_fraction", {1.0, 0.5, 0.25}, [this](double v) { setUpdateInterval(uint32_t(std::lround(1.0 / std::max(v, 1e-6)))); }};
}

// Both voxelizers' descriptor set: the raster path reads the draw records in its vertex stage and writes
// in its fragment stage; the compute one does all of it and reads the mesh itself.
static std::vector<render::Binding> voxelizeBindings(bool compute) {
  const VkShaderStageFlags writes = compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
  const VkShaderStageFlags reads = compute ? VK_SHADER_STAGE_COMPUTE_BIT : VK_SHADER_STAGE_VERTEX_BIT;
  constexpr VkDescriptorType kTexture = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  std::vector<render::Binding> b = {{DYNGI_VOXELIZE_BINDING_FRAGMENTS, kSSBO, writes},
                                    {DYNGI_VOXELIZE_BINDING_COUNTERS, kSSBO, writes},
                                    {DYNGI_VOXELIZE_BINDING_INSTANCES, kSSBO, reads},
                                    {DYNGI_VOXELIZE_BINDING_RANGES, kSSBO, reads},
                                    {DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX, kTexture, writes},
                                    {DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX, kTexture, writes},
                                    {DYNGI_VOXELIZE_BINDING_METALLIC_ROUGHNESS_TEX, kTexture, writes},
                                    {DYNGI_VOXELIZE_BINDING_NORMAL_TEX, kTexture, writes}};
  if (compute) b.insert(b.end(), {{DYNGI_VOXELIZE_BINDING_VERTICES, kSSBO, reads}, {DYNGI_VOXELIZE_BINDING_INDICES, kSSBO, reads}});
  return b;
}

render::Pipeline& VoxelScene::voxelizePipelineFor(uint32_t textureBits) {
  const bool alphaMask = textureBits & DYNGI_MATERIAL_ALPHA_MASK, normalTexture = textureBits & DYNGI_MATERIAL_NORMAL_TEX;
  textureBits &= DYNGI_MATERIAL_BASE_COLOR_TEX | DYNGI_MATERIAL_EMISSIVE_TEX | DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX;  // what it reads
  Pipeline& pipeline = voxelize_[textureBits | (alphaMask ? 8u : 0u) | (normalTexture ? 16u : 0u)];
  if (pipeline.handle()) return pipeline;
  Pipeline::GraphicsDesc d;
  d.vertex = normalTexture ? DYNGI_SHADER(spv_voxelize_tangent_vert) : DYNGI_SHADER(spv_voxelize_vert);
  d.geometry = DYNGI_SHADER(spv_voxelize_geom);
  d.fragment = DYNGI_SHADER(spv_voxelize_frag);
  render::setMeshVertexInput(d, /*normal=*/normalTexture, /*uv=*/true);
  if (normalTexture) render::setMeshTangentInput(d);
  d.pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  d.pushConstantBytes = sizeof(gpu::VoxelizePush);
  d.bindings = voxelizeBindings(/*compute=*/false);
  auto bit = [&](uint32_t b) { return (textureBits & b) ? 1u : 0u; };
  d.fragmentSpecialization = {bit(DYNGI_MATERIAL_BASE_COLOR_TEX), bit(DYNGI_MATERIAL_EMISSIVE_TEX), bit(DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX),
                              alphaMask ? 1u : 0u, normalTexture ? 1u : 0u};
  d.name = "voxelize";
  pipeline = Pipeline::graphics(ctx_, d);
  return pipeline;
}

render::Pipeline& VoxelScene::voxelizeSmallPipelineFor(uint32_t textureBits) {
  const bool alphaMask = textureBits & DYNGI_MATERIAL_ALPHA_MASK;
  textureBits &= DYNGI_MATERIAL_BASE_COLOR_TEX | DYNGI_MATERIAL_EMISSIVE_TEX | DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX;
  Pipeline& pipeline = voxelizeSmall_[textureBits | (alphaMask ? 8u : 0u)];
  if (pipeline.handle()) return pipeline;
  const std::vector<render::Binding> bindings = voxelizeBindings(/*compute=*/true);
  auto bit = [&](uint32_t b) { return (textureBits & b) ? 1u : 0u; };
  const uint32_t specialization[] = {bit(DYNGI_MATERIAL_BASE_COLOR_TEX), bit(DYNGI_MATERIAL_EMISSIVE_TEX), bit(DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX),
                                     alphaMask ? 1u : 0u};
  pipeline = Pipeline::compute(ctx_, DYNGI_SHADER(spv_voxelize_small_comp), bindings, sizeof(gpu::VoxelizePush), "voxelize small", specialization);
  return pipeline;
}

// Invocations one compute-voxelizer dispatch may hold: 64 a group, limit.x by limit.y groups, and under
// 2^31 (the shader's index).
static uint64_t maxInvocationsPerDispatch(glm::uvec2 limit) { return std::min<uint64_t>(uint64_t(limit.x) * limit.y * 64, uint64_t(1) << 31); }

std::vector<VoxelScene::ComputeVoxelizeDispatch> VoxelScene::splitComputeVoxelize(uint32_t instances, uint32_t triangles, glm::uvec2 limit) {
  std::vector<ComputeVoxelizeDispatch> out;
  if (instances == 0 || triangles == 0 || limit.x == 0 || limit.y == 0) return out;
  const uint64_t maxInvocations = maxInvocationsPerDispatch(limit);
  const uint32_t perDispatch = uint32_t(std::clamp<uint64_t>(maxInvocations / triangles, 1, instances));
  for (uint32_t first = 0; first < instances; first += perDispatch) {
    const uint32_t n = std::min(perDispatch, instances - first);
    const uint64_t groups = (uint64_t(n) * triangles + 63) / 64;
    const uint32_t x = uint32_t(std::min<uint64_t>(groups, limit.x));
    out.push_back({first, n, glm::uvec2(x, uint32_t((groups + x - 1) / x))});
  }
  return out;
}

glm::uvec2 VoxelScene::computeDispatchLimit() const {
  if (computeDispatchLimit_.x > 0 && computeDispatchLimit_.y > 0) return computeDispatchLimit_;
  const auto& l = ctx_.properties().limits;
  return {l.maxComputeWorkGroupCount[0], l.maxComputeWorkGroupCount[1]};
}

// Whether every triangle of the draw spans at most kComputeVoxelizeSpan voxels a side (a normal texture
// needs the raster path's vertex frame) and one instance fits a dispatch.
bool VoxelScene::voxelizesByCompute(const render::RenderSnapshot& snapshot, const render::DrawItem& d, const FragmentRanges::Estimate& estimate) const {
  const size_t triangles = snapshot.assets->mesh(d.mesh).indices.size() / 3;
  return computeVoxelization_ && snapshot.materialOf(d).normalTexture == scene::kNoTexture && triangles >= 1 &&
         triangles <= maxInvocationsPerDispatch(computeDispatchLimit()) &&
         estimate.widestTriangle <= kComputeVoxelizeSpan;
}

bool VoxelScene::record(render::FrameContext& frame) {
  if (!rebuildSvo_ || !haveVolume_) return false;
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t res = volume_.resolution, depth = volume_.depth();
  {
    render::ScopedPass scope(ctx_, frame.timer, cmd, "voxelize");
    // Neighbouring ranges and counters are filled by one command each (all of them after a full
    // re-voxelization): a fill per entity costs per command.
    std::vector<std::pair<uint64_t, uint64_t>> slotSpans, counterSpans;  // (first, count)
    for (const Range& r : rangesToEmpty_) slotSpans.push_back({r.first, r.capacity});
    for (size_t i : drawsToVoxelize_) {
      const Range& r = ranges_.at(frame.snapshot.draws[i].entity);
      slotSpans.push_back({r.first, r.capacity});
      counterSpans.push_back({r.counter, 1});
    }
    for (const auto& [first, count] : coalesceSpans(slotSpans)) vkCmdFillBuffer(cmd, fragments_.handle(), first * 16, count * 16, DYNGI_VOXEL_EMPTY);
    for (const auto& [first, count] : coalesceSpans(counterSpans)) vkCmdFillBuffer(cmd, counters_.handle(), first * 4, count * 4, 0);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (!drawsToVoxelize_.empty()) {
      writeVoxelizeRanges(frame);
      gpu::VoxelizePush pc{};
      pc.worldToVoxel = volume_.worldToVoxelMatrix();
      pc.resolution = res;
      // Both voxelizers: the fragment storage, the draw records, the ranges and the material's textures.
      auto writes = [&](const render::DrawItem& d) {
        DescriptorWrites w;
        w.storageBuffer(DYNGI_VOXELIZE_BINDING_FRAGMENTS, fragments_.handle())
            .storageBuffer(DYNGI_VOXELIZE_BINDING_COUNTERS, counters_.handle())
            .storageBuffer(DYNGI_VOXELIZE_BINDING_INSTANCES, frame.instances->records->handle())
            .storageBuffer(DYNGI_VOXELIZE_BINDING_RANGES, voxelizeRanges_.handle())
            .sampledImage(DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX, frame.textureView(frame.snapshot.materialOf(d).baseColorTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX, frame.textureView(frame.snapshot.materialOf(d).emissiveTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_VOXELIZE_BINDING_METALLIC_ROUGHNESS_TEX, frame.textureView(frame.snapshot.materialOf(d).metallicRoughnessTexture), frame.linearSampler,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(DYNGI_VOXELIZE_BINDING_NORMAL_TEX, frame.textureView(frame.snapshot.materialOf(d).normalTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        return w;
      };
      if (!rasterDraws_.empty()) {
        // No attachments: the fragment shader appends to the entity's range.
        render::RenderingScope rendering(cmd, res, res);
        auto pipelineFor = [&](const render::DrawItem& d) -> const Pipeline& { return voxelizePipelineFor(render::drawTextureBits(frame, d)); };
        render::drawBatched(frame, rasterDraws_, pipelineFor, [&](VkCommandBuffer c, const render::DrawItem& d, const Pipeline& pipeline) {
          writes(d).push(ctx_, c, pipeline);
          vkCmdPushConstants(c, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                             sizeof(pc), &pc);
        });
      }
      if (!computeDraws_.empty()) {
        render::computeWriteBarrier(cmd);  // an entity's draws may take both voxelizers: its counter's appends in order
        render::forEachBatch(frame, computeDraws_, [&](const render::DrawItem& d, const render::GpuMesh& mesh, uint32_t first, uint32_t count) {
          const Pipeline& pipeline = voxelizeSmallPipelineFor(render::drawTextureBits(frame, d));
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
          writes(d)
              .storageBuffer(DYNGI_VOXELIZE_BINDING_VERTICES, mesh.vertices.handle())
              .storageBuffer(DYNGI_VOXELIZE_BINDING_INDICES, mesh.indices.handle())
              .push(ctx_, cmd, pipeline);
          gpu::VoxelizePush batch = pc;
          batch.triangleCount = mesh.indexCount / 3;
          for (const ComputeVoxelizeDispatch& part : splitComputeVoxelize(count, batch.triangleCount, computeDispatchLimit())) {
            batch.firstInstance = first + part.firstInstance;
            batch.instanceCount = part.instanceCount;
            vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(batch), &batch);
            vkCmdDispatch(cmd, part.groups.x, part.groups.y, 1);
          }
        });
      }
    }
    render::computeWriteBarrier(cmd);
  }
  {
    const LeafAttributeTargets attributes{attributes_, attributeLeaves_, voxelAttributes_, fragmentsEmit()};
    svo_->record(frame, fragments_, counters_, depth, settings_.leafAttributes ? &attributes : nullptr);
  }
  stats_.rebuilt = true;
  return false;  // the voxel scene feeds other stages; it does not write indirect light
}

// Each voxelized draw's fragment range at its instance slot (the other slots are not drawn).
void VoxelScene::writeVoxelizeRanges(const render::FrameContext& frame) {
  const VkDeviceSize bytes = std::max<VkDeviceSize>(frame.snapshot.draws.size(), 1) * sizeof(gpu::VoxelizeRange);
  if (!voxelizeRanges_.valid() || voxelizeRanges_.size() < bytes)
    voxelizeRanges_ = Buffer(ctx_, bytes + bytes / 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "voxelize ranges");
  auto* out = static_cast<gpu::VoxelizeRange*>(voxelizeRanges_.mapped());
  for (size_t i : drawsToVoxelize_) {
    const Range& r = ranges_.at(frame.snapshot.draws[i].entity);
    out[frame.instances->slotOfDraw[i]] = gpu::VoxelizeRange{uint32_t(r.first), uint32_t(r.capacity), r.counter, 0u};
  }
  voxelizeRanges_.flush();
}

void VoxelScene::recordAfterLighting(render::FrameContext& frame) {
  if (settings_.debugView == VoxelDebugView::None || !haveVolume_) return;
  debugPass_->record(frame, *this, settings_.debugView);
}

void VoxelScene::frameFinished(render::VulkanContext&) {
  if (!stats_.rebuilt) return;
  counters_.invalidateForRead();
  const uint32_t* counts = static_cast<const uint32_t*>(counters_.mapped());
  stats_.overflowedEntities = 0;
  for (ecs::Entity e : voxelizedThisFrame_) {
    Range& r = ranges_.at(e);
    r.lastCount = counts[r.counter];
    if (r.lastCount > r.capacity) {
      ++stats_.overflowedEntities;
      dirty_.insert(e);  // next frame: a larger range
    }
  }
  stats_.fragments = ranges_.storedFragments();
  if (svo_->frameFinished(stats_)) storageMoved_ = true;  // the conservative SVO stands until the next build
  // The attributes are indexed by the leaf level's slots (empty siblings included), which can outnumber
  // the fragments: grow to them and build again.
  if (settings_.leafAttributes && stats_.leafSlots > attributeLeaves_) {
    allocateAttributes(stats_.leafSlots + stats_.leafSlots / 2);
    svo_->invalidateStaticOccupancy();  // the voxel attributes may miss the leaves that did not fit
    storageMoved_ = true;
  }
  // Far more than the build needs (the fragments shrank, the room emptied): the scratch sums follow.
  else if (settings_.leafAttributes && attributeLeaves_ > 2 * startingAttributeLeaves(stats_.fragmentCapacity, stats_.leafSlots))
    allocateAttributes(startingAttributeLeaves(stats_.fragmentCapacity, stats_.leafSlots));
  const render::ImageDesc& kept = voxelAttributes_.desc();
  stats_.totalBytes = fragments_.size() + svo_->bytes() + attributes_.size() + uint64_t(kept.width) * kept.height * kept.depth * 16;
}

void VoxelSyncSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  apply(tracker_.compute(world, assets_, ctx.lastRun));
}

void VoxelSyncSystem::apply(const ChangeSet& changes) {
  // Deforming meshes are in `deformed`: their vertices change without any component write.
  for (const auto* list : {&changes.moved, &changes.meshWritten, &changes.materials, &changes.deformed})
    for (ecs::Entity e : *list) voxels_.markDirty(e);
  for (ecs::Entity e : changes.removed) voxels_.markRemoved(e);
}

}  // namespace dyngi::gi
