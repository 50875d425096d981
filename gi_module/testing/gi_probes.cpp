#include "testing/gi_probes.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cmath>
#include <unordered_map>

#include <glm/gtc/packing.hpp>

#include "dyngi/engine/render/gpu_timer.h"
#include "voxel/shaders/voxel_shared.h"
#include "indirect/shaders/indirect_shared.h"
#include "voxel/svo_builder.h"
#include "spirv/svo_march.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

namespace {
template <class F>
F* featureOf(GiSystem& gi) {
  for (render::RenderFeature* f : gi.technique().features())
    if (auto* typed = dynamic_cast<F*>(f)) return typed;
  return nullptr;
}
}  // namespace

TemporalIndirect* temporalOf(GiSystem& gi) { return featureOf<TemporalIndirect>(gi); }
VplPaths* pathsOf(GiSystem& gi) {
  TemporalIndirect* t = temporalOf(gi);
  return t ? &t->paths() : nullptr;
}
ManyLights* manyLightsOf(GiSystem& gi) { return featureOf<ManyLights>(gi); }

VoxelProbe::VoxelProbe(VoxelScene& voxels) : voxels_(voxels) {}

uint64_t VoxelProbe::attributeLeaves() const { return voxels_.attributeLeaves_; }
uint64_t VoxelProbe::leafSlotBound() const { return voxels_.occupancyBound().leafSlots; }
uint64_t VoxelProbe::nodeGroupBound() const { return voxels_.occupancyBound().nodeGroups; }
uint64_t VoxelProbe::nodeGroupCapacity() const { return voxels_.svo_->nodeGroupCapacity(); }

// The march pipelines are made on first use: a probe that only reads back compiles nothing.
const render::Pipeline& VoxelProbe::marchPipeline(bool march) {
  render::Pipeline& p = march ? march_ : marchOff_;
  if (!p.handle()) {
    const Binding marchB[] = {{DYNGI_SVO_MARCH_BINDING_NODES, kSSBO, kCS},
                              {DYNGI_SVO_MARCH_BINDING_SEGMENTS, kSSBO, kCS},
                              {DYNGI_SVO_MARCH_BINDING_RESULTS, kSSBO, kCS}};
    const uint32_t spec[] = {march ? 1u : 0u};
    p = Pipeline::compute(voxels_.ctx_, DYNGI_SHADER(spv_svo_march_comp), marchB, sizeof(gpu::SvoMarchPush),
                          march ? "svo_march" : "svo_march_off", spec);
  }
  return p;
}

std::vector<uint32_t> VoxelProbe::readbackNodes() {
  render::Buffer& counters = voxels_.svo_->counters();
  counters.invalidateForRead();
  const auto* c = static_cast<const gpu::SvoCounters*>(counters.mapped());
  uint64_t groups = std::min<uint64_t>(c->groups.x, c->groups.y);
  return render::readbackBuffer<uint32_t>(voxels_.ctx_, voxels_.nodes().handle(), size_t(groups * 8));
}

std::vector<VoxelFragment> VoxelProbe::readbackFragments() {
  const uint64_t slots = voxels_.ranges_.highWater();
  std::vector<VoxelFragment> out;
  if (slots == 0) return out;
  const std::vector<glm::uvec4> stored = render::readbackBuffer<glm::uvec4>(voxels_.ctx_, voxels_.fragments_.handle(), size_t(slots));
  for (const glm::uvec4& f : stored) {
    if (f[0] == DYNGI_VOXEL_EMPTY) continue;
    VoxelFragment v;
    v.cell = glm::uvec3(f[0] & 1023u, (f[0] >> 10) & 1023u, (f[0] >> 20) & 1023u);
    v.albedo = glm::unpackUnorm4x8(f[1]);
    v.normal = glm::vec3(glm::unpackSnorm4x8(f[2]));
    // voxelize.frag's packEmission: rgb / 2^k as unorm8, k + 8 in the fourth byte (0: no emission).
    const glm::vec4 e = glm::unpackUnorm4x8(f[3]);
    v.emission = f[3] == 0 ? glm::vec3(0.0f) : glm::vec3(e) * std::exp2(float(int(f[3] >> 24) - 8));
    out.push_back(v);
  }
  return out;
}

DenseVoxelGrid VoxelProbe::readbackFragmentGrid() {
  DenseVoxelGrid grid(voxels_.volume().resolution);
  for (const VoxelFragment& f : readbackFragments()) grid.set(f.cell.x, f.cell.y, f.cell.z);
  return grid;
}

namespace {
// The voxel of a leaf's cell (its Morton code, svo_morton.glsl: bit 3i + axis is bit i of that axis).
glm::uvec3 voxelOfMortonCode(uint32_t code) {
  glm::uvec3 v(0u);
  for (uint32_t axis = 0; axis < 3; ++axis)
    for (uint32_t i = 0; i < 10; ++i) v[axis] |= ((code >> (3 * i + axis)) & 1u) << i;
  return v;
}
}  // namespace

VoxelProbe::LeafLevel VoxelProbe::readbackLeafLevel(bool withCells) {
  LeafLevel l;
  const uint32_t depth = voxels_.volume().depth();
  l.range = render::readbackBuffer<gpu::SvoLevel>(voxels_.ctx_, voxels_.levels().handle(), depth + 1)[depth].range;
  l.nodes = readbackNodes();
  if (withCells) {
    // Only a group's first slot is written (svo_morton.glsl's SVO_NODE_CELL): its siblings' follow.
    l.cells = render::readbackBuffer<uint32_t>(voxels_.ctx_, voxels_.nodeCells().handle(), l.nodes.size());
    for (size_t i = 0; i < l.cells.size(); ++i) l.cells[i] = l.cells[i & ~size_t(7)] + uint32_t(i & 7);
  }
  return l;
}

DenseVoxelGrid VoxelProbe::readbackLeafCells() {
  const LeafLevel l = readbackLeafLevel(true);
  DenseVoxelGrid grid(voxels_.volume().resolution);
  for (uint32_t i = 0; i < l.range.y && l.range.x + i < l.nodes.size(); ++i)
    if (l.nodes[l.range.x + i] != 0) {
      const glm::uvec3 v = voxelOfMortonCode(l.cells[l.range.x + i]);
      grid.set(v.x, v.y, v.z);
    }
  return grid;
}

VoxelProbe::LeafListCheck VoxelProbe::checkLeafList() {
  LeafListCheck check;
  const LeafLevel l = readbackLeafLevel(true);
  const glm::uvec4& range = l.range;
  const std::vector<uint32_t>& nodes = l.nodes;
  const std::vector<uint32_t> header = render::readbackBuffer<uint32_t>(voxels_.ctx_, voxels_.leafList().handle(), DYNGI_SVO_LEAF_LIST_HEADER);
  const uint64_t room = (voxels_.leafList().size() / 4 - DYNGI_SVO_LEAF_LIST_HEADER) / DYNGI_SVO_LEAF_ENTRY_UINTS;
  check.countFits = header[3] <= room;
  const uint32_t count = uint32_t(std::min<uint64_t>(header[3], room));
  const std::vector<uint32_t> list = render::readbackBuffer<uint32_t>(voxels_.ctx_, voxels_.leafList().handle(),
                                                                      DYNGI_SVO_LEAF_LIST_HEADER + size_t(count) * DYNGI_SVO_LEAF_ENTRY_UINTS);
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t node = list[DYNGI_SVO_LEAF_LIST_HEADER + DYNGI_SVO_LEAF_ENTRY_UINTS * k];
    check.entries.push_back(node);
    // The entry's cell is the node's.
    check.wrongCells += node >= l.cells.size() || l.cells[node] != list[DYNGI_SVO_LEAF_LIST_HEADER + DYNGI_SVO_LEAF_ENTRY_UINTS * k + 1];
  }
  const uint32_t perGroup = 64 * DYNGI_SVO_ITEMS_PER_INVOCATION;
  check.dispatchCovers = uint64_t(header[0]) * perGroup >= count && header[1] == 1 && header[2] == 1 && (count == 0 || header[0] > 0);
  std::vector<uint8_t> seen(nodes.size(), 0);
  for (uint32_t node : check.entries) {
    const bool leaf = node >= range.x && node - range.x < range.y && node < nodes.size() && nodes[node] != 0;
    if (!leaf) {
      ++check.stray;
      continue;
    }
    if (seen[node]++) ++check.duplicates;
  }
  for (uint32_t i = 0; i < range.y && range.x + i < nodes.size(); ++i)
    if (nodes[range.x + i] != 0) {
      ++check.occupied;
      if (!seen[range.x + i]) ++check.missed;
    }
  return check;
}

VoxelProbe::LeafAttributesCheck VoxelProbe::checkLeafAttributes() {
  LeafAttributesCheck check;
  const LeafLevel l = readbackLeafLevel(true);
  const glm::uvec4& range = l.range;
  // The leaf sums are scratch: every build leaves them zero.
  for (uint32_t word : render::readbackBuffer<uint32_t>(voxels_.ctx_, voxels_.attributes_.handle(),
                                                           size_t(voxels_.leafCapacity() * DYNGI_LEAF_ATTRIBUTE_INTS)))
    check.sumsLeft += word != 0;
  const uint64_t res = voxels_.volume().resolution;
  Image& image = voxels_.voxelAttributes_;
  const std::vector<uint8_t> bytes = render::readbackImageBytes(voxels_.ctx_, image);
  voxels_.ctx_.immediate([&](VkCommandBuffer cmd) {  // back to where the passes expect it
    image.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  });
  std::vector<glm::uvec4> texels(bytes.size() / sizeof(glm::uvec4));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(glm::uvec4));
  // The fragments' quantized values as the attribute pass sums them, per voxel (x | y << 10 | z << 20).
  struct Sums {
    uint32_t count = 0;
    glm::dvec3 albedo{0.0}, normal{0.0};
  };
  auto key = [](const glm::uvec3& v) { return v.x | (v.y << 10) | (v.z << 20); };
  std::unordered_map<uint32_t, Sums> expected;
  for (const VoxelFragment& f : readbackFragments()) {
    Sums& s = expected[key(f.cell)];
    ++s.count;
    s.albedo += glm::dvec3(glm::round(glm::vec3(f.albedo) * 255.0f)) / 255.0;
    s.normal += glm::dvec3(glm::round(glm::clamp(f.normal, -1.0f, 1.0f) * 127.0f)) / 127.0;
  }
  for (uint64_t i = 0; i < range.y && range.x + i < l.nodes.size(); ++i) {
    if (l.nodes[range.x + i] == 0) continue;
    ++check.leaves;
    // leaf_attributes.glsl's voxelAttributesAt(voxel).
    const glm::uvec3 cell = voxelOfMortonCode(l.cells[range.x + i]);
    const uint64_t texel = cell.x + res * (cell.y + res * cell.z);
    const glm::uvec4 t = texel < texels.size() ? texels[texel] : glm::uvec4(0u);
    const glm::dvec3 albedo(glm::unpackUnorm4x8(t.x)), normal(glm::unpackSnorm4x8(t.y));
    const auto found = expected.find(key(cell));
    const Sums s = found == expected.end() ? Sums{} : found->second;
    if ((t.x >> 24) != std::min(s.count, 255u)) {
      ++check.wrongCount;
      continue;
    }
    if (s.count > 255) continue;  // which fragments were summed is the GPU's order
    auto off = [](const glm::dvec3& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); };
    check.wrongAlbedo += off(albedo - s.albedo / double(s.count)) > 1.01 / 255.0;
    check.wrongNormal += off(normal - s.normal / double(s.count)) > 1.01 / 127.0;
  }
  return check;
}

double VoxelProbe::marchSegments(const std::vector<Segment>& segments, std::vector<uint8_t>& out, float epsVoxels) {
  return dispatchMarch(marchPipeline(true), segments, out, epsVoxels);
}

double VoxelProbe::marchSegmentsWithoutMarch(const std::vector<Segment>& segments, std::vector<uint8_t>& out) {
  return dispatchMarch(marchPipeline(false), segments, out, 1e-3f);
}

double VoxelProbe::dispatchMarch(const render::Pipeline& pipeline, const std::vector<Segment>& segments, std::vector<uint8_t>& out,
                                 float epsVoxels) {
  render::VulkanContext& ctx_ = voxels_.ctx_;
  const VoxelVolume& volume_ = voxels_.volume();
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
  render::GpuTimer timer(ctx_, render::GpuTimer::Mode::Timestamps, 2);
  auto t0 = std::chrono::steady_clock::now();
  ctx_.immediate([&](VkCommandBuffer cmd) {
    timer.beginFrame(cmd);
    uint32_t s = timer.begin(cmd, "svo_march");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    DescriptorWrites()
        .storageBuffer(DYNGI_SVO_MARCH_BINDING_NODES, voxels_.nodes().handle())
        .storageBuffer(DYNGI_SVO_MARCH_BINDING_SEGMENTS, segBuf.handle())
        .storageBuffer(DYNGI_SVO_MARCH_BINDING_RESULTS, results.handle())
        .push(ctx_, cmd, pipeline);
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

std::vector<VplReadback> readbackVpls(ManyLights& ml, bool withProbes) {
  std::vector<VplReadback> out;
  if (!ml.vpls_.valid()) return out;
  const uint32_t n = ml.perBounce_ * ml.settings_.vpl.bounces + (withProbes ? ml.tailProbeCount() : 0u);
  for (const gpu::GpuVpl& v : render::readbackBuffer<gpu::GpuVpl>(ml.ctx_, ml.vpls_.handle(), n))
    out.push_back({glm::vec3(v.position), v.position.w < 0 ? -1 : int(v.position.w + 0.5f), glm::vec3(v.normal), glm::vec3(v.flux)});
  return out;
}

}  // namespace dyngi::gi
