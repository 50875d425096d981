#include "dyngi/gi/voxel_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/scene/animation.h"
#include "shaders/shared/gi_gpu_types.h"
#include "spirv/svo_expand.comp.spv.h"
#include "spirv/svo_leaf_attributes.comp.spv.h"
#include "spirv/svo_level.comp.spv.h"
#include "spirv/svo_mark.comp.spv.h"
#include "spirv/svo_march.comp.spv.h"
#include "spirv/voxel_debug.comp.spv.h"
#include "spirv/voxelize.frag.spv.h"
#include "spirv/voxelize.geom.spv.h"
#include "spirv/voxelize.vert.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

const OptionTable<VoxelSettings>& VoxelSettings::table() {
  static const OptionTable<VoxelSettings> t = OptionTable<VoxelSettings>().add(
      {"voxel-res", "voxel volume resolution (the SVO's finest level)", 64, 512, /*powerOfTwo=*/true}, &VoxelSettings::resolution);
  return t;
}

namespace {
constexpr uint32_t kAttributeInts = 8;  // ints per leaf in the attribute buffer
constexpr uint32_t kMinNodeGroups = 1u << 12;  // the node pool never shrinks below this (128 KB)
}  // namespace

VoxelScene::VoxelScene(render::VulkanContext& ctx, const VoxelSettings& settings) : ctx_(ctx), settings_(settings) {
  uint32_t r = settings.resolution;
  if (r < 8 || r > 1024 || (r & (r - 1)) != 0)
    throw std::invalid_argument("voxel resolution must be a power of two in 8..1024, got " + std::to_string(r));

  const Binding markB[] = {{0, kSSBO, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}};
  mark_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_mark_comp), markB, sizeof(gpu::SvoMarkPush), "svo_mark");
  const Binding levelB[] = {{0, kSSBO, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}, {3, kSSBO, kCS}, {4, kSSBO, kCS}};
  level_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_level_comp), levelB, sizeof(gpu::SvoLevelPush), "svo_level");
  const Binding expandB[] = {{0, kSSBO, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}, {3, kSSBO, kCS}, {4, kSSBO, kCS}};
  expand_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_expand_comp), expandB, sizeof(gpu::SvoExpandPush), "svo_expand");
  const Binding attrB[] = {{0, kSSBO, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}, {3, kSSBO, kCS}};
  leafAttributes_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_leaf_attributes_comp), attrB, sizeof(gpu::SvoLeafAttributesPush),
                                     "svo_leaf_attributes");
  // One bit per cell of every level 0..depth (DYNGI_SVO_LEVEL_BASE): level depth + 1 would start here.
  uint32_t depth = 0;
  while ((1u << depth) < settings_.resolution) ++depth;
  const uint64_t pyramidBits = 8 + 8 * (((uint64_t(1) << (3 * depth)) - 1) / 7);
  occupancy_ = Buffer(ctx, (pyramidBits + 31) / 32 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      MemoryUsage::GpuOnly, "svo occupancy pyramid");
  staticOccupancy_ = Buffer(ctx, occupancy_.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            MemoryUsage::GpuOnly, "svo static occupancy pyramid");
  const Binding marchB[] = {{0, kSSBO, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}};
  march_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_march_comp), marchB, sizeof(gpu::SvoMarchPush), "svo_march");
  const uint32_t noMarch[] = {0u};
  marchOff_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_svo_march_comp), marchB, sizeof(gpu::SvoMarchPush), "svo_march_off", noMarch);
  const Binding debugB[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCS}, {1, kSSBO, kCS}, {2, kSSBO, kCS}, {3, kSSBO, kCS},
                            {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kCS}};
  debug_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_voxel_debug_comp), debugB, sizeof(gpu::VoxelDebugPush), "voxel_debug");

  // The first build gets the whole pool; afterwards it follows what the SVO uses (resizeNodePool).
  nodeGroupCapacity_ = std::max(settings.maxNodeGroups, 2u);
  nodes_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  nodeCells_ = Buffer(ctx, VkDeviceSize(nodeGroupCapacity_) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  levels_ = Buffer(ctx, sizeof(gpu::SvoLevel) * DYNGI_SVO_MAX_LEVELS, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                   MemoryUsage::Readback, "svo levels");
  svoCounters_ = Buffer(ctx, sizeof(gpu::SvoCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        MemoryUsage::Readback, "svo counters");
  reallocateFragments(1u << 16, {});
}

VoxelScene::~VoxelScene() = default;

void VoxelScene::setDebugView(VoxelDebugView v) {
  settings_.debugView = v;
  if (v == VoxelDebugView::Voxels && !settings_.leafAttributes) {  // the view colours voxels by albedo
    settings_.leafAttributes = true;
    vkDeviceWaitIdle(ctx_.device());
    attributes_ = Buffer(ctx_, stats_.fragmentCapacity * kAttributeInts * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly,
                         "voxel leaf attributes");
    storageMoved_ = true;  // build them
  }
}

void VoxelScene::setVolume(const VoxelVolume& v) {
  volume_ = v;
  volume_.resolution = settings_.resolution;
  haveVolume_ = true;
  allDirty_ = true;
}

void VoxelScene::ensureCapacity(uint64_t slots) {
  if (fragments_.valid() && fragments_.size() >= slots * 16) return;
  std::vector<VkBufferCopy> keep;
  if (fragments_.valid() && highWater_ > 0) keep.push_back({0, 0, highWater_ * 16});
  reallocateFragments(std::max<uint64_t>(slots + slots / 2, 1u << 16), keep);
}

void VoxelScene::reallocateFragments(uint64_t slots, const std::vector<VkBufferCopy>& keep) {
  vkDeviceWaitIdle(ctx_.device());
  Buffer fresh(ctx_, slots * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "voxel fragments");
  ctx_.immediate([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, fresh.handle(), 0, VK_WHOLE_SIZE, DYNGI_VOXEL_EMPTY);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (!keep.empty()) vkCmdCopyBuffer(cmd, fragments_.handle(), fresh.handle(), uint32_t(keep.size()), keep.data());
  });
  fragments_ = std::move(fresh);
  attributes_ = Buffer(ctx_, settings_.leafAttributes ? slots * kAttributeInts * 4 : 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       MemoryUsage::GpuOnly, "voxel leaf attributes");
  stats_.fragmentCapacity = slots;
  storageMoved_ = true;
}

uint64_t VoxelScene::movingCapacity(const Range& r) { return 2 * uint64_t(r.lastCount) + 64; }

VoxelScene::RangeNeed VoxelScene::rangeNeed(uint64_t estimate, const Range* previous) {
  if (!previous || previous->voxelizations == 0) return {estimate, estimate};
  // It overflowed: more than it held, whatever the estimate says.
  if (previous->lastCount > previous->capacity) {
    uint64_t n = std::max<uint64_t>(estimate, uint64_t(previous->lastCount) * 5 / 4 + 64);
    return {n, n};
  }
  // Known count: a moved or turned mesh rarely needs twice what it held (a thin sheet turning from an
  // axis to a diagonal comes closest); the estimate overshoots small triangles several times over. The
  // range is kept while it has a quarter of headroom, so a count that wobbles does not move it. A mesh
  // that grew (scaled up, deformed larger) since that count needs it scaled by how much its estimate
  // grew: sized from the old count alone it would overflow and lose voxels for a frame.
  Range scaled = *previous;
  if (previous->lastEstimate > 0 && estimate > previous->lastEstimate)
    scaled.lastCount = uint32_t(std::min<double>(double(previous->lastCount) * double(estimate) / double(previous->lastEstimate), 4.0e9));
  return {std::min<uint64_t>(estimate, uint64_t(scaled.lastCount) * 5 / 4 + 64), std::min(estimate, movingCapacity(scaled))};
}

void VoxelScene::compactRanges() {
  // Ranges are sized by an estimate that overshoots small triangles several times over, and a moved
  // entity leaves a hole where its old range was. Once the counts are known, entities voxelized once
  // (static) keep exactly their fragments; moving ones keep their slack (their count changes as they
  // turn). Valid fragments sit at the start of a range (the voxelizer appends), so a copy moves them.
  std::vector<std::pair<ecs::Entity, Range*>> order;
  for (auto& [e, r] : ranges_) order.push_back({e, &r});
  std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.second->first < y.second->first; });
  std::vector<VkBufferCopy> keep;
  uint64_t next = 0;
  for (auto& [e, r] : order) {
    uint64_t used = std::min<uint64_t>(r->lastCount, r->capacity);
    uint64_t capacity = r->voxelizations > 1 ? std::min(r->capacity, movingCapacity(*r)) : used;
    if (used > 0) keep.push_back({r->first * 16, next * 16, used * 16});
    r->first = next;
    r->capacity = capacity;
    next += capacity;
  }
  highWater_ = next;
  reallocateFragments(std::max<uint64_t>(next + next / 4, 1u << 16), keep);
}

uint64_t VoxelScene::estimateFragments(const scene::MeshData& mesh, const glm::mat4& m) const {
  // Per triangle: its area projected on the dominant plane plus its perimeter (the columns it can touch),
  // times two for the depth spread inside a column, plus slack. Overshoots are caught after the frame.
  double sum = 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    glm::vec3 a(m * glm::vec4(mesh.positions[mesh.indices[t]], 1)), b(m * glm::vec4(mesh.positions[mesh.indices[t + 1]], 1)),
        c(m * glm::vec4(mesh.positions[mesh.indices[t + 2]], 1));
    glm::vec3 n = glm::abs(glm::cross(b - a, c - a));
    double area = 0.5 * std::max({n.x, n.y, n.z});
    double perimeter = glm::length(b - a) + glm::length(c - b) + glm::length(a - c);
    sum += 2.0 * (area + perimeter + 2.0);
  }
  return uint64_t(sum * 1.25) + 64;
}

void VoxelScene::relayout(const render::RenderSnapshot& snapshot) {
  (void)snapshot;
  ranges_.clear();
  freeCounters_.clear();
  counterCount_ = 0;
  highWater_ = 0;
  rangesToEmpty_.clear();
}

void VoxelScene::prepare(render::VulkanContext&, const render::RenderSnapshot& snapshot) {
  drawsToVoxelize_.clear();
  rangesToEmpty_.clear();
  voxelizedThisFrame_.clear();
  rebuildSvo_ = false;
  stats_.rebuilt = false;
  stats_.entitiesVoxelized = 0;
  if (!snapshot.assets) return;
  ++frameIndex_;
  if (!haveVolume_) {
    volume_ = VoxelVolume::around(snapshot.sceneBounds, settings_.resolution, settings_.padding);
    haveVolume_ = true;
    allDirty_ = true;
  }
  const glm::mat4 toVoxel = volume_.worldToVoxelMatrix();

  // Entities that disappeared from the draw list count as removed.
  std::unordered_set<ecs::Entity> present;
  for (const auto& d : snapshot.draws) present.insert(d.entity);
  for (const auto& [e, r] : ranges_)
    if (!present.count(e)) removed_.insert(e);

  // Compact when the ranges hold more than twice what they need (counts from the last frame): after
  // the first frame, and again as moved entities leave holes.
  if (!allDirty_ && highWater_ > (1u << 16)) {
    uint64_t used = 0;
    for (const auto& [e, r] : ranges_)
      used += r.voxelizations > 1 ? std::min(r.capacity, movingCapacity(r)) : std::min<uint64_t>(r.lastCount, r.capacity);
    if (highWater_ > 2 * used) compactRanges();
  }
  if (allDirty_) {
    rebuildStaticOccupancy_ = true;
    relayout(snapshot);
    for (const auto& d : snapshot.draws) dirty_.insert(d.entity);
    allDirty_ = false;
    rebuildSvo_ = true;
  }
  std::vector<ecs::Entity> removedNow;
  for (ecs::Entity e : removed_) {
    auto it = ranges_.find(e);
    if (it == ranges_.end()) continue;
    removedNow.push_back(e);
    rangesToEmpty_.push_back(it->second);
    freeCounters_.push_back(it->second.counter);
    ranges_.erase(it);
    rebuildSvo_ = true;
  }
  removed_.clear();
  drawsToVoxelize_.clear();
  uint64_t newHighWater = highWater_;
  std::vector<std::pair<ecs::Entity, Range>> planned;
  for (size_t i = 0; i < snapshot.draws.size(); ++i) {
    const auto& d = snapshot.draws[i];
    if (!dirty_.count(d.entity)) continue;
    const scene::MeshData& mesh = snapshot.assets->mesh(d.mesh);
    auto it = ranges_.find(d.entity);
    Range r = it != ranges_.end() ? it->second : Range{};
    const uint64_t estimate = estimateFragments(mesh, toVoxel * d.model);
    RangeNeed need = rangeNeed(estimate, it != ranges_.end() ? &r : nullptr);
    if (it == ranges_.end() || r.capacity < need.minimum) {
      if (it != ranges_.end()) rangesToEmpty_.push_back(r);  // the old place must not keep stale voxels
      Range fresh;
      fresh.first = newHighWater;
      fresh.capacity = need.fresh;
      fresh.voxelizations = r.voxelizations;
      if (it != ranges_.end()) fresh.counter = r.counter;
      else if (!freeCounters_.empty()) fresh.counter = freeCounters_.back(), freeCounters_.pop_back();
      else fresh.counter = counterCount_++;
      newHighWater += need.fresh;
      r = fresh;
    }
    r.lastEstimate = estimate;
    planned.push_back({d.entity, r});
    drawsToVoxelize_.push_back(i);
  }
  ensureCapacity(newHighWater);  // grows by copying: nothing already voxelized is lost
  for (auto& [e, r] : planned) {
    r.written = true;
    r.lastVoxelizedFrame = frameIndex_;
    ++r.voxelizations;
    ranges_[e] = r;
    voxelizedThisFrame_.push_back(e);
  }
  highWater_ = newHighWater;
  dirty_.clear();
  if (!drawsToVoxelize_.empty() || storageMoved_) rebuildSvo_ = true;
  storageMoved_ = false;
  uint64_t countersBytes = uint64_t(std::max(counterCount_, 1u)) * 4;
  if (!counters_.valid() || counters_.size() < countersBytes) {
    vkDeviceWaitIdle(ctx_.device());
    Buffer grown(ctx_, std::max<uint64_t>(countersBytes * 2, 1024), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "voxel counters");
    if (counters_.valid()) std::memcpy(grown.mapped(), counters_.mapped(), counters_.size());
    counters_ = std::move(grown);
  }
  stats_.entitiesVoxelized = uint32_t(drawsToVoxelize_.size());
  if (rebuildSvo_) planOccupancy(removedNow);
}

void VoxelScene::planOccupancy(const std::vector<ecs::Entity>& removed) {
  // The static pyramid is stale when one of its entities was voxelized again (moved, deformed) or
  // removed; it is worth rebuilding when a moving entity has settled.
  for (ecs::Entity e : voxelizedThisFrame_) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (ecs::Entity e : removed) rebuildStaticOccupancy_ |= staticEntities_.count(e) > 0;
  for (const auto& [e, r] : ranges_) rebuildStaticOccupancy_ |= !isMoving(r) && !staticEntities_.count(e);
  if (rebuildStaticOccupancy_) {
    staticEntities_.clear();
    for (const auto& [e, r] : ranges_)
      if (!isMoving(r)) staticEntities_.insert(e);
  }
  // One chunk per mark workgroup (64 invocations x DYNGI_SVO_ITEMS_PER_INVOCATION slots), cut from the
  // ranges: the static entities' first (only when the static pyramid is rebuilt), then the moving ones'.
  const uint64_t chunkSlots = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
  std::vector<glm::uvec2> chunks;
  stats_.slotsMarked = 0;
  stats_.staticEntities = uint32_t(staticEntities_.size());
  auto cut = [&](bool wantStatic) {
    uint32_t n = 0;
    for (const auto& [e, r] : ranges_) {
      if (staticEntities_.count(e) != size_t(wantStatic)) continue;
      stats_.slotsMarked += r.capacity;
      for (uint64_t a = r.first; a < r.first + r.capacity; a += chunkSlots, ++n)
        chunks.push_back(glm::uvec2(uint32_t(a), uint32_t(std::min(a + chunkSlots, r.first + r.capacity))));
    }
    return n;
  };
  staticChunks_ = rebuildStaticOccupancy_ ? cut(true) : 0;
  movingChunks_ = cut(false);
  const VkDeviceSize bytes = std::max<VkDeviceSize>(chunks.size() * sizeof(glm::uvec2), 16);
  if (!markChunks_.valid() || markChunks_.size() < bytes) {
    vkDeviceWaitIdle(ctx_.device());  // the last frame may still read the old list
    markChunks_ = Buffer(ctx_, bytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "svo mark chunks");
  }
  if (!chunks.empty()) markChunks_.upload(chunks.data(), chunks.size() * sizeof(glm::uvec2));
}

void VoxelScene::recordMark(VkCommandBuffer cmd, const render::Buffer& target, uint32_t firstChunk, uint32_t chunkCount) {
  if (chunkCount == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mark_.handle());
  DescriptorWrites().storageBuffer(0, fragments_.handle()).storageBuffer(1, target.handle()).storageBuffer(2, markChunks_.handle()).push(ctx_, cmd, mark_);
  const gpu::SvoMarkPush mp{firstChunk, volume_.depth()};
  vkCmdPushConstants(cmd, mark_.layout(), kCS, 0, sizeof(mp), &mp);
  vkCmdDispatch(cmd, chunkCount, 1, 1);
}

render::Pipeline& VoxelScene::voxelizePipelineFor(bool baseColorTexture, bool emissiveTexture) {
  Pipeline& pipeline = voxelize_[(baseColorTexture ? 1 : 0) | (emissiveTexture ? 2 : 0)];
  if (pipeline.handle()) return pipeline;
  Pipeline::GraphicsDesc d;
  d.vertex = DYNGI_SHADER(spv_voxelize_vert);
  d.geometry = DYNGI_SHADER(spv_voxelize_geom);
  d.fragment = DYNGI_SHADER(spv_voxelize_frag);
  render::setMeshVertexInput(d, /*normal=*/false, /*uv=*/true);
  d.pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  d.pushConstantBytes = sizeof(gpu::VoxelizePush);
  d.bindings = {{0, kSSBO, VK_SHADER_STAGE_FRAGMENT_BIT},
                {1, kSSBO, VK_SHADER_STAGE_FRAGMENT_BIT},
                {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
  d.fragmentSpecialization = {baseColorTexture ? 1u : 0u, emissiveTexture ? 1u : 0u};
  d.name = "voxelize";
  pipeline = Pipeline::graphics(ctx_, d);
  return pipeline;
}

bool VoxelScene::record(render::FrameContext& frame) {
  if (!rebuildSvo_ || !haveVolume_) return false;
  VkCommandBuffer cmd = frame.cmd;
  const uint32_t res = volume_.resolution, depth = volume_.depth();
  {
    render::ScopedPass scope(ctx_, frame.timer, cmd, "voxelize");
    for (const Range& r : rangesToEmpty_)
      vkCmdFillBuffer(cmd, fragments_.handle(), r.first * 16, r.capacity * 16, DYNGI_VOXEL_EMPTY);
    for (size_t i : drawsToVoxelize_) {
      const Range& r = ranges_.at(frame.snapshot.draws[i].entity);
      vkCmdFillBuffer(cmd, fragments_.handle(), r.first * 16, r.capacity * 16, DYNGI_VOXEL_EMPTY);
      vkCmdFillBuffer(cmd, counters_.handle(), uint64_t(r.counter) * 4, 4, 0);
    }
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    if (!drawsToVoxelize_.empty()) {
      VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
      ri.renderArea = {{0, 0}, {res, res}};
      ri.layerCount = 1;
      vkCmdBeginRendering(cmd, &ri);
      render::setFullViewport(cmd, res, res);
      const Pipeline* bound = nullptr;
      const glm::mat4 toVoxel = volume_.worldToVoxelMatrix();
      for (size_t i : drawsToVoxelize_) {
        const render::DrawItem& d = frame.snapshot.draws[i];
        const render::GpuMesh* mesh = frame.meshes[i];
        if (!mesh || mesh->indexCount == 0) continue;
        const Range& r = ranges_.at(d.entity);
        const Pipeline& pipeline =
            voxelizePipelineFor(d.material.baseColorTexture != scene::kNoTexture, d.material.emissiveTexture != scene::kNoTexture);
        if (&pipeline != bound) {
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.handle());
          bound = &pipeline;
        }
        gpu::VoxelizePush pc;
        pc.modelToVoxel = toVoxel * d.model;
        pc.range = glm::uvec4(uint32_t(r.first), uint32_t(r.capacity), r.counter, res);
        pc.albedo = glm::vec4(glm::vec3(d.material.baseColor) * (1.0f - d.material.metallic), 0.0f);
        pc.emission = glm::vec4(d.material.emissive, 0.0f);
        DescriptorWrites()
            .storageBuffer(0, fragments_.handle())
            .storageBuffer(1, counters_.handle())
            .sampledImage(2, frame.textureView(d.material.baseColorTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .sampledImage(3, frame.textureView(d.material.emissiveTexture), frame.linearSampler, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .push(ctx_, cmd, pipeline);
        vkCmdPushConstants(cmd, pipeline.layout(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(pc), &pc);
        render::drawMesh(cmd, *mesh);
      }
      vkCmdEndRendering(cmd);
    }
    render::computeWriteBarrier(cmd);
  }
  {
    render::ScopedPass scope(ctx_, frame.timer, cmd, "svo_build");
    gpu::SvoCounters init{};
    init.groups = glm::uvec4(1, nodeGroupCapacity_, 0, 0);
    vkCmdUpdateBuffer(cmd, svoCounters_.handle(), 0, sizeof(init), &init);
    // 1. Every fragment marks its cells in the occupancy pyramid: the static entities' once into the
    // static pyramid, which each build copies, then the moving entities' on top.
    if (rebuildStaticOccupancy_) {
      vkCmdFillBuffer(cmd, staticOccupancy_.handle(), 0, VK_WHOLE_SIZE, 0);
      render::computeWriteBarrier(cmd);
      recordMark(cmd, staticOccupancy_, 0, staticChunks_);
      render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT);
      rebuildStaticOccupancy_ = false;
    }
    const VkBufferCopy whole{0, 0, occupancy_.size()};
    vkCmdCopyBuffer(cmd, staticOccupancy_.handle(), occupancy_.handle(), 1, &whole);
    render::computeWriteBarrier(cmd);
    recordMark(cmd, occupancy_, staticChunks_, movingChunks_);
    render::computeWriteBarrier(cmd);
    const uint32_t slots = uint32_t(highWater_);
    const uint32_t perGroup = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
    // 2. Top down, level by level: the occupied nodes get their children, flagged from the pyramid.
    for (uint32_t l = 0; l <= depth; ++l) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, level_.handle());
      DescriptorWrites()
          .storageBuffer(0, levels_.handle())
          .storageBuffer(1, svoCounters_.handle())
          .storageBuffer(2, nodes_.handle())
          .storageBuffer(3, nodeCells_.handle())
          .storageBuffer(4, occupancy_.handle())
          .push(ctx_, cmd, level_);
      const gpu::SvoLevelPush lp{l};
      vkCmdPushConstants(cmd, level_.layout(), kCS, 0, sizeof(lp), &lp);
      vkCmdDispatch(cmd, 1, 1, 1);
      render::computeWriteBarrier(cmd);
      if (l == depth) break;  // leaves: their range is known, they are never subdivided
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, expand_.handle());
      DescriptorWrites()
          .storageBuffer(0, nodes_.handle())
          .storageBuffer(1, nodeCells_.handle())
          .storageBuffer(2, occupancy_.handle())
          .storageBuffer(3, levels_.handle())
          .storageBuffer(4, svoCounters_.handle())
          .push(ctx_, cmd, expand_);
      const gpu::SvoExpandPush ep{l, depth};
      vkCmdPushConstants(cmd, expand_.layout(), kCS, 0, sizeof(ep), &ep);
      vkCmdDispatchIndirect(cmd, levels_.handle(), VkDeviceSize(l) * sizeof(gpu::SvoLevel) + offsetof(gpu::SvoLevel, dispatch));
      render::computeWriteBarrier(cmd);
    }
    if (settings_.leafAttributes) {
      // Leaf attributes, kept apart from the nodes.
      vkCmdFillBuffer(cmd, attributes_.handle(), 0, VK_WHOLE_SIZE, 0);
      render::computeWriteBarrier(cmd);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, leafAttributes_.handle());
      DescriptorWrites()
          .storageBuffer(0, fragments_.handle())
          .storageBuffer(1, nodes_.handle())
          .storageBuffer(2, levels_.handle())
          .storageBuffer(3, attributes_.handle())
          .push(ctx_, cmd, leafAttributes_);
      const gpu::SvoLeafAttributesPush ap{depth, uint32_t(stats_.fragmentCapacity), slots};
      vkCmdPushConstants(cmd, leafAttributes_.layout(), kCS, 0, sizeof(ap), &ap);
      vkCmdDispatch(cmd, std::max(dispatchGroups(slots, perGroup), 1u), 1, 1);
      render::computeWriteBarrier(cmd);
    }
  }
  stats_.rebuilt = true;
  return false;  // the voxel scene feeds other stages; it does not write indirect light
}

void VoxelScene::recordAfterLighting(render::FrameContext& frame) {
  if (settings_.debugView == VoxelDebugView::None || !haveVolume_) return;
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "voxel_debug_view");
  render::RenderTargets& t = frame.targets;
  t.hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, debug_.handle());
  DescriptorWrites()
      .uniformBuffer(0, frame.frameUniforms.handle())
      .storageBuffer(1, nodes_.handle())
      .storageBuffer(2, levels_.handle())
      .storageBuffer(3, attributes_.handle())
      .storageImage(4, t.hdr.view())
      .push(ctx_, frame.cmd, debug_);
  const gpu::VoxelDebugPush pc{glm::vec4(volume_.origin, 1.0f / volume_.voxelSize), volume_.depth(), float(volume_.resolution),
                               settings_.debugView == VoxelDebugView::SvoSteps ? 1u : 0u};
  vkCmdPushConstants(frame.cmd, debug_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(frame.cmd, (t.width + 7) / 8, (t.height + 7) / 8, 1);
}

void VoxelScene::frameFinished(render::VulkanContext&) {
  if (!stats_.rebuilt) return;
  counters_.invalidateForRead();
  svoCounters_.invalidateForRead();
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
  uint64_t total = 0;
  for (auto& [e, r] : ranges_) total += std::min<uint64_t>(r.lastCount, r.capacity);
  stats_.fragments = total;
  const auto* c = static_cast<const gpu::SvoCounters*>(svoCounters_.mapped());
  uint64_t groups = std::min<uint64_t>(c->groups.x, c->groups.y);
  stats_.nodes = groups * 8;
  stats_.leaves = c->groups.w;
  stats_.poolOverflow = c->groups.z != 0;
  stats_.svoBytes = stats_.nodes * 4;
  if (stats_.poolOverflow && nodeGroupCapacity_ >= settings_.maxNodeGroups)
    std::fprintf(stderr, "dyngi: warning: SVO node pool overflow (%u groups); raise maxNodeGroups\n", settings_.maxNodeGroups);
  // Keep the pool between 4/3 and 8 times what the SVO uses: grow before it fills (an overflowing build
  // is conservative: childless nodes count as occupied, so it is rebuilt next frame), shrink after the
  // first build, which had the whole pool.
  uint64_t want = nodeGroupCapacity_;
  if (stats_.poolOverflow || groups * 4 > uint64_t(nodeGroupCapacity_) * 3) want = std::max<uint64_t>(2ull * nodeGroupCapacity_, 2 * groups);
  else if (groups * 8 < nodeGroupCapacity_) want = 2 * groups;
  want = std::clamp<uint64_t>(want, std::min<uint32_t>(kMinNodeGroups, settings_.maxNodeGroups), settings_.maxNodeGroups);
  if (want != nodeGroupCapacity_) resizeNodePool(uint32_t(want), groups);
  if (stats_.poolOverflow && want > groups) storageMoved_ = true;  // the conservative SVO stands until the next build
  stats_.totalBytes = fragments_.size() + nodes_.size() + nodeCells_.size() + occupancy_.size() + attributes_.size();
}

void VoxelScene::resizeNodePool(uint32_t groups, uint64_t keepGroups) {
  vkDeviceWaitIdle(ctx_.device());
  Buffer fresh(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo nodes");
  keepGroups = std::min<uint64_t>(keepGroups, groups);
  if (keepGroups > 0)  // the current SVO stays readable until the next build
    ctx_.immediate([&](VkCommandBuffer cmd) {
      VkBufferCopy copy{0, 0, keepGroups * 8 * 4};
      vkCmdCopyBuffer(cmd, nodes_.handle(), fresh.handle(), 1, &copy);
    });
  nodes_ = std::move(fresh);
  nodeCells_ = Buffer(ctx_, VkDeviceSize(groups) * 8 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "svo node cells");
  nodeGroupCapacity_ = groups;
}

std::vector<uint32_t> VoxelScene::readbackNodes() {
  svoCounters_.invalidateForRead();
  const auto* c = static_cast<const gpu::SvoCounters*>(svoCounters_.mapped());
  uint64_t groups = std::min<uint64_t>(c->groups.x, c->groups.y);
  VkDeviceSize bytes = groups * 8 * 4;
  Buffer host(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "svo readback");
  ctx_.immediate([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(cmd, nodes_.handle(), host.handle(), 1, &copy);
  });
  host.invalidateForRead();
  const uint32_t* p = static_cast<const uint32_t*>(host.mapped());
  return std::vector<uint32_t>(p, p + groups * 8);
}

std::vector<VoxelFragment> VoxelScene::readbackFragments() {
  std::vector<VoxelFragment> out;
  if (highWater_ == 0) return out;
  VkDeviceSize bytes = highWater_ * 16;
  Buffer host(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "fragment readback");
  ctx_.immediate([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(cmd, fragments_.handle(), host.handle(), 1, &copy);
  });
  host.invalidateForRead();
  const uint32_t* p = static_cast<const uint32_t*>(host.mapped());
  for (uint64_t i = 0; i < highWater_; ++i) {
    const uint32_t* f = p + i * 4;
    if (f[0] == DYNGI_VOXEL_EMPTY) continue;
    VoxelFragment v;
    v.cell = glm::uvec3(f[0] & 1023u, (f[0] >> 10) & 1023u, (f[0] >> 20) & 1023u);
    v.albedo = glm::unpackUnorm4x8(f[1]);
    // voxelize.frag's packEmission: rgb / 2^k as unorm8, k + 8 in the fourth byte (0: no emission).
    const glm::vec4 e = glm::unpackUnorm4x8(f[3]);
    v.emission = f[3] == 0 ? glm::vec3(0.0f) : glm::vec3(e) * std::exp2(float(int(f[3] >> 24) - 8));
    out.push_back(v);
  }
  return out;
}

DenseVoxelGrid VoxelScene::readbackFragmentGrid() {
  DenseVoxelGrid grid(volume_.resolution);
  for (const VoxelFragment& f : readbackFragments()) grid.set(f.cell.x, f.cell.y, f.cell.z);
  return grid;
}

double VoxelScene::marchSegments(const std::vector<Segment>& segments, std::vector<uint8_t>& out, float epsVoxels) {
  return dispatchMarch(march_, segments, out, epsVoxels);
}

double VoxelScene::marchSegmentsWithoutMarch(const std::vector<Segment>& segments, std::vector<uint8_t>& out) {
  return dispatchMarch(marchOff_, segments, out, 1e-3f);
}

double VoxelScene::dispatchMarch(const render::Pipeline& pipeline, const std::vector<Segment>& segments, std::vector<uint8_t>& out,
                                 float epsVoxels) {
  out.assign(segments.size(), 0);
  if (segments.empty()) return 0.0;
  std::vector<glm::vec4> packed(segments.size() * 2);
  for (size_t i = 0; i < segments.size(); ++i) {
    packed[2 * i] = glm::vec4(segments[i].from, 1.0f);
    packed[2 * i + 1] = glm::vec4(segments[i].to, 1.0f);
  }
  Buffer segBuf(ctx_, packed.size() * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "march segments");
  segBuf.upload(packed.data(), packed.size() * 16);
  Buffer results(ctx_, segments.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "march results");
  render::GpuTimer timer(ctx_, 2);
  auto t0 = std::chrono::steady_clock::now();
  ctx_.immediate([&](VkCommandBuffer cmd) {
    timer.beginFrame(cmd);
    uint32_t s = timer.begin(cmd, "svo_march");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    DescriptorWrites().storageBuffer(0, nodes_.handle()).storageBuffer(1, segBuf.handle()).storageBuffer(2, results.handle()).push(ctx_, cmd, pipeline);
    const gpu::SvoMarchPush pc{glm::vec4(volume_.origin, 1.0f / volume_.voxelSize), uint32_t(segments.size()), volume_.depth(),
                               float(volume_.resolution), epsVoxels};
    vkCmdPushConstants(cmd, pipeline.layout(), kCS, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, dispatchGroups(uint32_t(segments.size()), 64), 1, 1);
    timer.end(cmd, s);
    render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                          VK_ACCESS_2_HOST_READ_BIT);
  });
  double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  timer.resolve();
  lastMarchWallMs_ = wallMs;
  results.invalidateForRead();
  const uint32_t* r = static_cast<const uint32_t*>(results.mapped());
  for (size_t i = 0; i < segments.size(); ++i) out[i] = r[i] ? 1 : 0;
  return timer.results().empty() ? 0.0 : timer.results()[0].second;
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
