#include "techniques/temporal/temporal_indirect.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include "dyngi/gi/job_pool.h"
#include "techniques/temporal/shaders/temporal_shared.h"
#include "spirv/temporal_reproject.comp.spv.h"
#include "indirect/indirect_passes.h"
#include "indirect/reduced_screen.h"
#include "spirv/temporal_gather.comp.spv.h"

#include "gpu_aliases.h"
#include "shaders/shared/bounce_tail.h"

namespace dyngi::gi {

TemporalIndirect::TemporalIndirect(render::VulkanContext& ctx, VplPaths& paths, VoxelScene* voxels, const EmbreeScene* bvh)
    : ctx_(ctx), paths_(paths), voxels_(voxels), bvh_(bvh), settings_(paths.settings()) {
  const TemporalOptions& settings = settings_;
  if (settings.visibility == VisibilityBackend::Svo && !voxels) throw std::invalid_argument("SVO visibility needs a VoxelScene");
  if (settings.visibility == VisibilityBackend::Bvh && !bvh) throw std::invalid_argument("BVH visibility needs an EmbreeScene");
  sets_ = std::min(paths.settings().temporalSets, uint32_t(DYNGI_MAX_TEMPORAL_SETS));
  perSet_ = (paths.settings().vpl.vpls + sets_ - 1) / sets_;
  gathered_ = perSet_;
  tailStride_ = std::clamp(settings.vpl.bounceTailStride, 1u, 4u);
  lastRendered_.assign(sets_, -1);
  const Binding accumulate[] = {{DYNGI_TEMPORAL_GATHER_BINDING_SET_SAMPLES, kStorageImage, kCS},
                                {DYNGI_TEMPORAL_GATHER_BINDING_SUMS, kStorageImage, kCS},
                                {DYNGI_TEMPORAL_GATHER_BINDING_QUEUE, kSSBO, kCS},
                                {DYNGI_TEMPORAL_GATHER_BINDING_QUEUE_ARGS, kSSBO, kCS}};
  gatherPass_ = std::make_unique<IndirectGatherPass>(ctx, DYNGI_SHADER(spv_temporal_gather_comp), accumulate, uint32_t(sizeof(gpu::AccumulatePush)),
                                                     "temporal_gather");
  filterPass_ = std::make_unique<IndirectFilterPass>(ctx);
  reduced_ = std::make_unique<ReducedScreen>(ctx);
  maxSetsPerFrame_ = std::clamp(settings.catchUpSets, 1u, sets_);
  // With the bounce tail a set's slots can hold one probe per gathered VPL after them (prepare).
  const uint32_t slotsBound = perSet_ * (settings.vpl.bounceTail ? 2u : 1u);
  vpls_ = Buffer(ctx, VkDeviceSize(slotsBound) * maxSetsPerFrame_ * sizeof(gpu::GpuVpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload,
                 "temporal vpls");
  // Sized as the reprojection shader declares it (a uniform array).
  cameras_ = Buffer(ctx, DYNGI_MAX_TEMPORAL_SETS * sizeof(gpu::TemporalSetCamera), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Upload,
                    "set cameras");
  bits_ = Buffer(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "visibility bits");
  queueArgs_ = Buffer(ctx, sizeof(gpu::TemporalQueue),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      MemoryUsage::GpuOnly, "temporal reprojection queue args");
  const Binding b[] = {{DYNGI_TEMPORAL_REPROJECT_BINDING_FRAME, kUBO, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_SET_SAMPLES, kStorageImage, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_CAMERAS, kUBO, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_SUMS, kStorageImage, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_FILTER_INPUT, kStorageImage, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE, kSSBO, kCS},
                       {DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE_ARGS, kSSBO, kCS}};
  reprojectPipeline_ = Pipeline::compute(ctx, DYNGI_SHADER(spv_temporal_reproject_comp), b, sizeof(gpu::AccumulatePush), "temporal_reproject");
}

TemporalIndirect::~TemporalIndirect() = default;

uint32_t TemporalIndirect::setsRendered() const {
  uint32_t n = 0;
  for (int64_t f : lastRendered_) n += f >= 0;
  return n;
}

void TemporalIndirect::resize(render::VulkanContext& ctx, uint32_t fullWidth, uint32_t fullHeight) {
  width_ = fullWidth;
  height_ = fullHeight;
  const uint32_t width = ReducedScreen::reducedSize(fullWidth, gatherScale()), height = ReducedScreen::reducedSize(fullHeight, gatherScale());
  auto make = [&](VkFormat f, uint32_t layers, VkImageViewType viewType, const char* name) {
    render::ImageDesc d;
    d.width = width;
    d.height = height;
    d.layers = layers;
    d.format = f;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.viewType = viewType;
    d.name = name;
    return Image(ctx, d);
  };
  accumulated_ = make(VK_FORMAT_R32G32B32A32_UINT, 1, VK_IMAGE_VIEW_TYPE_2D, "temporal accumulated");  // filter_input.glsl's packing
  setSamples_ = make(VK_FORMAT_R32G32_UINT, sets_, VK_IMAGE_VIEW_TYPE_2D_ARRAY, "temporal set samples (rgb9e5, depth)");
  sums_ = make(VK_FORMAT_R32G32B32A32_SFLOAT, 1, VK_IMAGE_VIEW_TYPE_2D, "temporal sums");
  queue_ = Buffer(ctx, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "temporal reprojection queue");
  setCameras_.assign(sets_, glm::mat4(0.0f));
  lastCamera_ = glm::mat4(0.0f);
  std::fill(lastRendered_.begin(), lastRendered_.end(), -1);  // stored buffers are gone
}

bool TemporalIndirect::screenReduced() const { return ReducedScreen::reduces(width_, height_, gatherScale()); }

void TemporalIndirect::prepare(render::VulkanContext& ctx, const render::RenderSnapshot&) {
  if (accumulated_.valid() && (accumulated_.desc().width != ReducedScreen::reducedSize(width_, gatherScale()) ||
                               accumulated_.desc().height != ReducedScreen::reducedSize(height_, gatherScale())))
    resize(ctx, width_, height_);  // a GI budget moved the gather scale: the sets start over
  // Sets mostly stale (a light switched or jumped, and the burst reshot their VPLs) leave the average
  // until they are gathered again: the running sums hold them, so this frame reprojects in full.
  droppedSets_ = false;
  for (uint32_t s = 0; s < sets_; ++s)
    if (lastRendered_[s] >= 0 && settings_.dropStaleSets < 1.0f && paths_.setStaleFraction(s) > settings_.dropStaleSets) {
      lastRendered_[s] = -1;
      droppedSets_ = true;
    }
  // Which sets: one a frame, or while some set has no stored light (at the start, or dropped as stale)
  // up to catchUpSets of them; each a set whose VPLs changed, else the one gathered longest ago.
  uint32_t unrendered = 0;
  for (int64_t f : lastRendered_) unrendered += f < 0;
  const uint32_t count = std::clamp(unrendered, 1u, maxSetsPerFrame_);
  frameSets_.clear();
  auto chosen = [&](uint32_t s) { return std::find(frameSets_.begin(), frameSets_.end(), s) != frameSets_.end(); };
  while (frameSets_.size() < count) {
    int best = -1;
    for (int pass = 0; pass < 2 && best < 0; ++pass)
      for (uint32_t s = 0; s < sets_; ++s) {
        if (chosen(s) || (pass == 0 && !paths_.setDirty(s) && lastRendered_[s] >= 0)) continue;
        if (best < 0 || lastRendered_[s] < lastRendered_[size_t(best)]) best = int(s);
      }
    frameSets_.push_back(uint32_t(best));
  }
  currentSet_ = frameSets_.back();
  // Upload those sets' VPLs (set k: VPLs[T i + k]), each or an evenly spread subset of it
  // (setVplsPerFrame), one after another. With the bounce tail each set's slots go on with the probes of
  // its last-bounce VPLs (PathVpl::probePosition), gathered as the next bounce with every later one's
  // light (bounceTailScale); the last bounce keeps its own flux. The slots are padded to the same count
  // for every set.
  const auto& all = paths_.vpls();
  const uint32_t B = paths_.bounces();
  const double stride = double(perSet_) / double(gathered_);
  auto poolIndex = [&](uint32_t j, uint32_t set) { return std::min(perSet_ - 1, uint32_t(double(j) * stride)) * sets_ + set; };
  const bool probes = settings_.vpl.bounceTail;
  // With a tail stride, one path in each run of that many gathers its probe, standing for the run.
  const uint32_t paths = uint32_t(all.size() / B), tailStride = std::max(1u, tailStride_);
  auto probeWeight = [&](uint32_t index) -> uint32_t {
    if (!probes || index >= all.size() || index % B != B - 1) return 0;
    const uint32_t path = index / B, run = path / tailStride;
    return gpu::bounceTailChosenInRun(run, tailStride, paths) == path ? gpu::bounceTailRunLength(run, tailStride, paths) : 0;
  };
  uint32_t probeSlots = 0;
  for (uint32_t set = 0; probes && set < sets_; ++set) {
    uint32_t n = 0;
    for (uint32_t j = 0; j < gathered_; ++j) n += probeWeight(poolIndex(j, set)) > 0;
    probeSlots = std::max(probeSlots, n);
  }
  slots_ = gathered_ + probeSlots;
  gpu::GpuVpl absent{};
  absent.position = glm::vec4(0, 0, 0, -1);
  std::vector<gpu::GpuVpl> gpuVpls(size_t(slots_) * frameSets_.size(), absent);
  setVpls_.assign(gpuVpls.size(), TemporalVpl{{}, {}, false});  // the BVH visibility's copy
  auto put = [&](size_t slot, glm::vec3 position, glm::vec3 normal, glm::vec3 flux, uint32_t bounce, uint32_t path) {
    const float lum = 0.2126f * flux.r + 0.7152f * flux.g + 0.0722f * flux.b;
    gpuVpls[slot] = {glm::vec4(position, float(bounce)), glm::vec4(normal, float(path)), glm::vec4(flux, lum)};
    setVpls_[slot] = {position, normal, lum > 0.0f};
  };
  const glm::vec3 tail = paths_.bounceTailScale();  // the probes carry every bounce after the last
  for (size_t k = 0; k < frameSets_.size(); ++k) {
    size_t probe = k * slots_ + gathered_;
    for (uint32_t j = 0; j < gathered_; ++j) {
      const uint32_t index = poolIndex(j, frameSets_[k]);
      if (index >= all.size() || !all[index].valid || !all[index].placed) continue;
      const PathVpl& v = all[index];
      const uint32_t bounce = index % B, path = index / B;
      put(k * slots_ + j, v.position, v.normal, v.flux, bounce, path);
      if (const uint32_t weight = probeWeight(index); weight > 0 && !v.probeSurface.isNull())
        put(probe++, v.probePosition, v.probeNormal, v.flux * v.probeAlbedo * tail * float(weight), B, path);
    }
  }
  dropTrappedVpls(gpuVpls);
  vpls_.upload(gpuVpls.data(), gpuVpls.size() * sizeof(gpu::GpuVpl));
}

// SVO visibility starts a VPL's segments liftVoxels off its surface. A VPL with another surface closer
// than that along its normal (the ceiling over a lamp hung 2 cm under it) would start past that surface
// and light the room through it; what it really lights is the surface in front of it, which the path's
// next VPL carries. So it is left out of the gather; one Embree ray per VPL gathered says which.
void TemporalIndirect::dropTrappedVpls(std::vector<gpu::GpuVpl>& gpuVpls) {
  trappedVpls_ = 0;
  if (settings_.visibility != VisibilityBackend::Svo || !bvh_ || !voxels_ || !voxels_->hasVolume()) return;
  const float lift = settings_.vpl.liftVoxels * voxels_->volume().voxelSize;
  if (!(lift > 0.0f)) return;
  std::vector<Segment> segments;
  std::vector<size_t> slots;
  for (size_t i = 0; i < gpuVpls.size(); ++i) {
    const gpu::GpuVpl& v = gpuVpls[i];
    if (v.position.w < 0.0f) continue;
    const glm::vec3 p(v.position), n(v.normal);
    segments.push_back({p, p + n * lift});
    slots.push_back(i);
  }
  std::vector<uint8_t> occluded(segments.size());
  bvh_->occluded(segments.data(), segments.size(), occluded.data(), 0.05f * lift);  // off its own surface
  for (size_t k = 0; k < slots.size(); ++k)
    if (occluded[k]) {
      gpuVpls[slots[k]].position.w = -1.0f;
      ++trappedVpls_;
    }
}

namespace {
// The Embree visibility's bits of one set: one per pixel and VPL it gathers, in whole 32-bit words.
size_t visibilityWordsPerSet(uint32_t width, uint32_t height, uint32_t perPixel) { return (size_t(width) * height * perPixel + 31) / 32; }
}  // namespace

void TemporalIndirect::computeBvhVisibility(render::FrameContext& frame, uint32_t perPixel) {
  auto t0 = std::chrono::steady_clock::now();
  frame.submitAndWait();  // this frame's G-buffer, on the CPU
  std::vector<glm::vec4> pos = render::readbackImage(ctx_, frame.targets.position);
  std::vector<glm::vec4> nrm = render::readbackImage(ctx_, frame.targets.normal);
  const uint32_t W = frame.targets.width, H = frame.targets.height, K = interleave(), K2 = K * K;
  // One block of bits per set gathered this frame (GatherPush::firstBit: where set k's block starts).
  const size_t wordsPerSet = visibilityWordsPerSet(W, H, perPixel), words = wordsPerSet * frameSets_.size();
  std::vector<uint32_t> bits(words, 0);
  const float scale = frame.snapshot.sceneBounds.valid() ? glm::length(frame.snapshot.sceneBounds.extent()) : 1.0f;
  const float lift = 2e-3f * scale;
  // Rows on the job pool; a row's bits may share a word with the next row's, so bits are set atomically.
  parallelFor(0, H, 4, [&](size_t rowBegin, size_t rowEnd) {
    std::vector<Segment> segs;
    std::vector<uint64_t> bitIndex;
    std::vector<uint8_t> occ;
    for (uint32_t y = uint32_t(rowBegin); y < rowEnd; ++y) {
      segs.clear();
      bitIndex.clear();
      for (uint32_t x = 0; x < W; ++x) {
        size_t p = size_t(y) * W + x;
        if (pos[p].w == 0.0f) continue;
        glm::vec3 n = glm::normalize(glm::vec3(nrm[p]));
        glm::vec3 from = glm::vec3(pos[p]) + n * lift;
        uint32_t s = (x % K) + K * (y % K);
        for (size_t set = 0; set < frameSets_.size(); ++set)
          for (uint32_t m = 0, i = s; i < slots_; i += K2, ++m) {
            const TemporalVpl& v = setVpls_[set * slots_ + i];
            if (!v.valid) continue;
            segs.push_back({from, v.position + v.normal * lift});
            bitIndex.push_back(set * wordsPerSet * 32 + p * perPixel + m);
          }
      }
      occ.resize(segs.size());
      bvh_->occluded(segs.data(), segs.size(), occ.data(), 1e-5f * scale);
      for (size_t k = 0; k < segs.size(); ++k)
        if (!occ[k]) std::atomic_ref<uint32_t>(bits[bitIndex[k] >> 5]).fetch_or(1u << (bitIndex[k] & 31u), std::memory_order_relaxed);
    }
  });
  VkDeviceSize bytes = std::max<VkDeviceSize>(words * 4, 16);
  if (bits_.size() < bytes) bits_ = Buffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "visibility bits");
  bits_.upload(bits.data(), words * 4);
  bvhMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool TemporalIndirect::record(render::FrameContext& frame) {
  if (!accumulated_.valid()) return false;
  if (settings_.visibility == VisibilityBackend::Svo && !voxels_->hasVolume()) return false;
  recordScreen(reduced_->begin(frame, gatherScale()));
  reduced_->finish(frame);
  return true;
}

void TemporalIndirect::recordScreen(render::FrameContext& frame) {
  const uint32_t K = interleave(), K2 = K * K;
  const uint32_t perPixel = (slots_ + K2 - 1) / K2;
  // (No ScopedPass here: the mid-frame submit would split a debug label across command buffers; the
  // CPU time is reported as lastBvhVisibilityMs.)
  if (settings_.visibility == VisibilityBackend::Bvh) computeBvhVisibility(frame, perPixel);
  // This frame's camera for the sets about to be gathered.
  const dyngi::gpu::FrameUniforms& view = frame.uniforms;  // what this frame's shaders see
  gpu::TemporalSetCamera cam{view.viewProj, view.cameraPos, view.pixelRay0, view.pixelRayStepX, view.pixelRayStepY};
  std::vector<uint32_t> wasStored;
  for (uint32_t set : frameSets_) {
    cameras_.upload(&cam, sizeof(cam), VkDeviceSize(set) * sizeof(gpu::TemporalSetCamera));
    wasStored.push_back(lastRendered_[set] >= 0 ? 1u : 0u);
  }
  // Incremental accumulation when nothing but this set changed for this camera (see temporal_accumulate.glsl);
  // a full reprojection otherwise (several sets gathered, a set dropped, the camera moved), and every 256
  // frames to wash out float drift in the running sums.
  const bool incremental = settings_.incrementalAccumulation && frameSets_.size() == 1 && cam.viewProj == lastCamera_ && wasStored[0] &&
                           setCameras_[currentSet_] == cam.viewProj && !droppedSets_ && frameCounter_ % 256 != 0;
  for (uint32_t set : frameSets_) {
    lastRendered_[set] = int64_t(frameCounter_);
    paths_.markSetRendered(set);
    setCameras_[set] = cam.viewProj;
  }
  ++frameCounter_;
  lastCamera_ = cam.viewProj;
  uint32_t validMask = 0, sameCamera = 0;
  for (uint32_t s = 0; s < sets_; ++s) {
    if (lastRendered_[s] >= 0) validMask |= 1u << s;
    if (setCameras_[s] == cam.viewProj) sameCamera |= 1u << s;
  }
  {
    IndirectGatherPass::Inputs in;
    gpu::GatherPush& pc = in.push;
    if (voxels_ && voxels_->hasVolume()) {
      const VoxelVolume& vol = voxels_->volume();
      pc.worldToVoxel = glm::vec4(vol.origin, 1.0f / vol.voxelSize);
      pc.liftVoxels = settings_.vpl.liftVoxels;
      pc.voxelResolution = float(vol.resolution);
      pc.visibility = DYNGI_VISIBILITY_SVO;
      pc.svoDepth = vol.depth();
    } else {
      pc.voxelResolution = 1.0f;
      pc.visibility = DYNGI_VISIBILITY_NONE;
    }
    pc.distanceClamp = settings_.vpl.distanceClamp;
    pc.clampSpread = settings_.vpl.clampSpreadStretch();
    pc.tailBounce = settings_.vpl.bounceTail ? paths_.bounces() : 0u;  // the probes' bounce (prepare)
    pc.luminanceThreshold = settings_.vpl.luminanceThreshold;
    pc.vplCount = slots_;
    // A subset of the set (setVplsPerFrame) stands for the whole set, its probes for all of the set's.
    pc.estimatedCount = uint32_t((uint64_t(slots_) * perSet_ + gathered_ / 2) / gathered_);
    pc.interleave = K;
    if (settings_.visibility == VisibilityBackend::Bvh) pc.visibility = DYNGI_VISIBILITY_BITS;
    if (settings_.visibility == VisibilityBackend::None) pc.visibility = DYNGI_VISIBILITY_NONE;
    pc.bitsPerPixel = perPixel;
    for (render::Image* img : {&setSamples_, &sums_})
      img->transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    gpu::AccumulatePush acc{};
    acc.setCount = sets_;
    acc.storedSets = validMask;
    acc.setsFromThisCamera = sameCamera;
    // With an unchanged camera the gather queues the few pixels whose surface changed; otherwise every
    // pixel needs the full reprojection and the pass runs over all of them.
    acc.incremental = incremental ? 1u : 0u;
    acc.reprojectionCutoff = settings_.reprojectionCutoff;
    if (incremental) {
      const gpu::TemporalQueue empty{glm::uvec4(0u, 1u, 1u, 0u)};
      vkCmdUpdateBuffer(frame.cmd, queueArgs_.handle(), 0, sizeof(empty), &empty);
      render::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    in.vpls = vpls_.handle();
    in.nodes = voxels_ ? voxels_->nodes().handle() : vpls_.handle();
    in.bits = bits_.handle();
    in.extraWrites = [&](DescriptorWrites& w) {
      w.storageImage(DYNGI_TEMPORAL_GATHER_BINDING_SET_SAMPLES, setSamples_.view())
          .storageImage(DYNGI_TEMPORAL_GATHER_BINDING_SUMS, sums_.view())
          .storageBuffer(DYNGI_TEMPORAL_GATHER_BINDING_QUEUE, queue_.handle())
          .storageBuffer(DYNGI_TEMPORAL_GATHER_BINDING_QUEUE_ARGS, queueArgs_.handle());
    };
    in.extraPush = &acc;
    // One gather per set (each stores its own layer); the full reprojection after the last sums them all.
    for (size_t k = 0; k < frameSets_.size(); ++k) {
      if (k > 0) render::computeWriteBarrier(frame.cmd);
      pc.firstVpl = uint32_t(k) * slots_;
      pc.firstBit = uint32_t(k * visibilityWordsPerSet(frame.targets.width, frame.targets.height, perPixel) * 32);
      acc.currentSet = frameSets_[k];
      acc.currentSetWasStored = wasStored[k];
      gatherPass_->record(frame, accumulated_, in);
    }
    recordReprojection(frame, acc, incremental);
  }
  filterPass_->record(frame, accumulated_, K, settings_.vpl);
}

void TemporalIndirect::recordReprojection(render::FrameContext& frame, const gpu::AccumulatePush& push, bool queued) {
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "reproject");
  VkCommandBuffer cmd = frame.cmd;
  render::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  accumulated_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reprojectPipeline_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_TEMPORAL_REPROJECT_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_TEMPORAL_REPROJECT_BINDING_SET_SAMPLES, setSamples_.view())
      .uniformBuffer(DYNGI_TEMPORAL_REPROJECT_BINDING_CAMERAS, cameras_.handle())
      .storageImage(DYNGI_TEMPORAL_REPROJECT_BINDING_SUMS, sums_.view())
      .storageImage(DYNGI_TEMPORAL_REPROJECT_BINDING_FILTER_INPUT, accumulated_.view())
      .storageBuffer(DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE, queue_.handle())
      .storageBuffer(DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE_ARGS, queueArgs_.handle())
      .push(ctx_, cmd, reprojectPipeline_);
  vkCmdPushConstants(cmd, reprojectPipeline_.layout(), kCS, 0, sizeof(push), &push);
  if (queued) {
    vkCmdDispatchIndirect(cmd, queueArgs_.handle(), 0);
  } else {
    const uint64_t pixels = uint64_t(frame.targets.width) * frame.targets.height;
    vkCmdDispatch(cmd, uint32_t((pixels + 63) / 64), 1, 1);
  }
}

}  // namespace dyngi::gi
