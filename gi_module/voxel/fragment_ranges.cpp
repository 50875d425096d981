#include "dyngi/gi/fragment_ranges.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dyngi::gi {

FragmentRanges::Estimate FragmentRanges::estimate(const scene::MeshData& mesh, const glm::mat4& m, uint32_t resolution) {
  // Per triangle: its area projected on the dominant plane plus its perimeter (the columns it can touch),
  // times two for the depth spread inside a column, plus slack; overshoots are caught after the frame.
  // A triangle gives a voxel one fragment at most, so the voxels of its bounding box (touching ones
  // included: the overlap test counts contact) bound it exactly: small triangles take that bound, with
  // no slack, and many small instances do not each reserve the slack of a large mesh.
  constexpr float kTouch = 1e-3f;  // voxel units; above the voxelizer's contact epsilon
  double loose = 0;
  uint64_t bounded = 0;
  float widest = 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    glm::vec3 a(m * glm::vec4(mesh.positions[mesh.indices[t]], 1)), b(m * glm::vec4(mesh.positions[mesh.indices[t + 1]], 1)),
        c(m * glm::vec4(mesh.positions[mesh.indices[t + 2]], 1));
    const glm::vec3 extent = glm::max(a, glm::max(b, c)) - glm::min(a, glm::min(b, c));
    const glm::vec3 sum = a + b + c;  // min/max drop a NaN: judge the vertices
    const bool finite = std::isfinite(sum.x) && std::isfinite(sum.y) && std::isfinite(sum.z);
    widest = finite ? std::max({widest, extent.x, extent.y, extent.z}) : std::numeric_limits<float>::infinity();
    glm::vec3 n = glm::abs(glm::cross(b - a, c - a));
    double area = 0.5 * std::max({n.x, n.y, n.z});
    double perimeter = glm::length(b - a) + glm::length(c - b) + glm::length(a - c);
    const double estimate = 2.0 * (area + perimeter + 2.0);
    glm::vec3 lo = glm::floor(glm::min(a, glm::min(b, c)) - kTouch), hi = glm::floor(glm::max(a, glm::max(b, c)) + kTouch);
    if (resolution > 0) {  // the voxelizer clips to the volume
      lo = glm::max(lo, glm::vec3(0.0f));
      hi = glm::min(hi, glm::vec3(float(resolution - 1)));
      if (glm::any(glm::lessThan(hi, lo))) continue;
    }
    const glm::dvec3 span = glm::dvec3(hi - lo) + 1.0;
    const double boxVoxels = span.x * span.y * span.z;
    if (boxVoxels <= estimate) bounded += uint64_t(boxVoxels);
    else loose += estimate;
  }
  return {bounded + (loose > 0 ? uint64_t(loose * 1.25) + 16 : 0), widest};
}

FragmentRanges::Need FragmentRanges::need(uint64_t estimate, const FragmentRange* previous) {
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
  FragmentRange scaled = *previous;
  if (previous->lastEstimate > 0 && estimate > previous->lastEstimate)
    scaled.lastCount = uint32_t(std::min<double>(double(previous->lastCount) * double(estimate) / double(previous->lastEstimate), 4.0e9));
  return {std::min<uint64_t>(estimate, uint64_t(scaled.lastCount) * 5 / 4 + 64), std::min(estimate, movingCapacity(scaled))};
}

void FragmentRanges::clear() {
  ranges_.clear();
  freeCounters_.clear();
  counterCount_ = 0;
  highWater_ = 0;
}

std::optional<FragmentRange> FragmentRanges::remove(ecs::Entity e) {
  auto it = ranges_.find(e);
  if (it == ranges_.end()) return std::nullopt;
  FragmentRange r = it->second;
  freeCounters_.push_back(r.counter);
  ranges_.erase(it);
  return r;
}

FragmentRange FragmentRanges::plan(ecs::Entity e, uint64_t estimate, uint64_t& highWater, std::vector<FragmentRange>& toEmpty) {
  auto it = ranges_.find(e);
  FragmentRange r = it != ranges_.end() ? it->second : FragmentRange{};
  const Need n = need(estimate, it != ranges_.end() ? &r : nullptr);
  if (it == ranges_.end() || r.capacity < n.minimum) {
    if (it != ranges_.end()) toEmpty.push_back(r);  // the old place must not keep stale voxels
    FragmentRange fresh;
    fresh.first = highWater;
    fresh.capacity = n.fresh;
    fresh.voxelizations = r.voxelizations;
    if (it != ranges_.end()) fresh.counter = r.counter;
    else if (!freeCounters_.empty()) fresh.counter = freeCounters_.back(), freeCounters_.pop_back();
    else fresh.counter = counterCount_++;
    highWater += n.fresh;
    r = fresh;
  }
  r.lastEstimate = estimate;
  return r;
}

void FragmentRanges::commit(ecs::Entity e, FragmentRange r, uint64_t frame) {
  r.written = true;
  r.lastVoxelizedFrame = frame;
  ++r.voxelizations;
  ranges_[e] = r;
}

bool FragmentRanges::wantsCompaction() const {
  if (highWater_ <= kMinCompactSlots) return false;
  uint64_t used = 0;
  for (const auto& [e, r] : ranges_)
    used += r.voxelizations > 1 ? std::min(r.capacity, movingCapacity(r)) : std::min<uint64_t>(r.lastCount, r.capacity);
  return highWater_ > 2 * used;
}

std::vector<SlotCopy> FragmentRanges::compact() {
  // Ranges are sized by an estimate that overshoots small triangles several times over, and a moved
  // entity leaves a hole where its old range was. Once the counts are known, entities voxelized once
  // (static) keep exactly their fragments; moving ones keep their slack (their count changes as they
  // turn). Valid fragments sit at the start of a range (the voxelizer appends), so a copy moves them.
  std::vector<FragmentRange*> order;
  for (auto& [e, r] : ranges_) order.push_back(&r);
  std::sort(order.begin(), order.end(), [](const FragmentRange* x, const FragmentRange* y) { return x->first < y->first; });
  std::vector<SlotCopy> keep;
  uint64_t next = 0;
  for (FragmentRange* r : order) {
    uint64_t used = std::min<uint64_t>(r->lastCount, r->capacity);
    uint64_t capacity = r->voxelizations > 1 ? std::min(r->capacity, movingCapacity(*r)) : used;
    if (used > 0) keep.push_back({r->first, next, used});
    r->first = next;
    r->capacity = capacity;
    next += capacity;
  }
  highWater_ = next;
  return keep;
}

uint64_t FragmentRanges::storedFragments() const {
  uint64_t total = 0;
  for (const auto& [e, r] : ranges_) total += std::min<uint64_t>(r.lastCount, r.capacity);
  return total;
}

}  // namespace dyngi::gi
