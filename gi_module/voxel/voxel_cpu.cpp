#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "dyngi/gi/voxel.h"
#include "voxel/shaders/voxel_shared.h"

namespace dyngi::gi {

VoxelVolume VoxelVolume::around(const scene::Aabb& bounds, uint32_t resolution, float padding) {
  VoxelVolume v;
  v.resolution = resolution;
  glm::vec3 c = bounds.valid() ? bounds.center() : glm::vec3(0.0f);
  glm::vec3 e = bounds.valid() ? bounds.extent() : glm::vec3(1.0f);
  float side = std::max({e.x, e.y, e.z, 1e-3f}) * (1.0f + 2.0f * padding);
  v.voxelSize = side / float(resolution);
  v.origin = c - glm::vec3(0.5f * side);
  return v;
}

glm::mat4 VoxelVolume::worldToVoxelMatrix() const {
  glm::mat4 m(1.0f / voxelSize);
  m[3] = glm::vec4(-origin / voxelSize, 1.0f);
  return m;
}

uint32_t VoxelVolume::depth() const {
  uint32_t d = 0;
  while ((1u << d) < resolution) ++d;
  return d;
}

namespace {
bool separates(const glm::dvec3& axis, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& h) {
  double p0 = glm::dot(a, axis), p1 = glm::dot(b, axis), p2 = glm::dot(c, axis);
  double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}
}  // namespace

bool triangleOverlapsBox(const glm::dvec3& center, const glm::dvec3& h, const glm::dvec3& ta, const glm::dvec3& tb,
                         const glm::dvec3& tc) {
  glm::dvec3 a = ta - center, b = tb - center, c = tc - center;
  for (int i = 0; i < 3; ++i)
    if (std::max({a[i], b[i], c[i]}) < -h[i] || std::min({a[i], b[i], c[i]}) > h[i]) return false;
  glm::dvec3 e[3] = {b - a, c - b, a - c};
  if (separates(glm::cross(e[0], e[1]), a, b, c, h)) return false;
  for (auto& ed : e) {
    if (separates({0.0, -ed.z, ed.y}, a, b, c, h)) return false;
    if (separates({ed.z, 0.0, -ed.x}, a, b, c, h)) return false;
    if (separates({-ed.y, ed.x, 0.0}, a, b, c, h)) return false;
  }
  return true;
}

size_t DenseVoxelGrid::count() const {
  size_t n = 0;
  for (uint8_t b : bits_) n += b;
  return n;
}

bool DenseVoxelGrid::occluded(const glm::dvec3& a, const glm::dvec3& b, double eps) const {
  glm::dvec3 d = b - a;
  double len = glm::length(d);
  if (len <= 2.0 * eps) return false;
  glm::dvec3 dir = d / len;
  const double R = double(res_);
  double t = eps, tEnd = len - eps;
  for (int i = 0; i < 3; ++i) {  // clip to the volume
    if (dir[i] == 0.0) {
      if (a[i] < 0.0 || a[i] > R) return false;
      continue;
    }
    double t0 = (0.0 - a[i]) / dir[i], t1 = (R - a[i]) / dir[i];
    t = std::max(t, std::min(t0, t1));
    tEnd = std::min(tEnd, std::max(t0, t1));
  }
  if (t >= tEnd) return false;
  glm::dvec3 p = a + dir * t;
  glm::ivec3 v, step;
  glm::dvec3 tMax, tDelta;
  for (int i = 0; i < 3; ++i) {
    // The cell the ray is moving into when p sits on a face (the SVO uses the same rule).
    double f = std::floor(p[i]);
    int vi = int(f);
    if (p[i] == f && dir[i] < 0.0) vi -= 1;
    v[i] = std::clamp(vi, 0, int(res_) - 1);
    step[i] = dir[i] > 0.0 ? 1 : (dir[i] < 0.0 ? -1 : 0);
    double boundary = dir[i] > 0.0 ? double(v[i] + 1) : double(v[i]);
    tMax[i] = dir[i] != 0.0 ? (boundary - a[i]) / dir[i] : std::numeric_limits<double>::infinity();
    tDelta[i] = dir[i] != 0.0 ? 1.0 / std::abs(dir[i]) : std::numeric_limits<double>::infinity();
  }
  while (true) {
    if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= int(res_) || v.y >= int(res_) || v.z >= int(res_)) return false;
    if (get(uint32_t(v.x), uint32_t(v.y), uint32_t(v.z))) return true;
    int axis = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
    if (tMax[axis] >= tEnd) return false;
    v[axis] += step[axis];
    tMax[axis] += tDelta[axis];
  }
}

uint32_t DenseVoxelGrid::distanceToOccupied(const glm::ivec3& v, uint32_t cap) const {
  for (uint32_t r = 0; r <= cap; ++r) {
    int ri = int(r);
    for (int z = v.z - ri; z <= v.z + ri; ++z)
      for (int y = v.y - ri; y <= v.y + ri; ++y)
        for (int x = v.x - ri; x <= v.x + ri; ++x) {
          if (std::max({std::abs(x - v.x), std::abs(y - v.y), std::abs(z - v.z)}) != ri) continue;
          if (x < 0 || y < 0 || z < 0 || x >= int(res_) || y >= int(res_) || z >= int(res_)) continue;
          if (get(uint32_t(x), uint32_t(y), uint32_t(z))) return r;
        }
  }
  return cap + 1;
}

DenseVoxelGrid voxelizeBruteForce(const std::vector<glm::vec3>& tris, uint32_t res) {
  DenseVoxelGrid g(res);
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    glm::dvec3 a(tris[t]), b(tris[t + 1]), c(tris[t + 2]);
    glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    glm::ivec3 i0 = glm::clamp(glm::ivec3(glm::floor(lo)), glm::ivec3(0), glm::ivec3(int(res) - 1));
    glm::ivec3 i1 = glm::clamp(glm::ivec3(glm::floor(hi)), glm::ivec3(0), glm::ivec3(int(res) - 1));
    for (int z = i0.z; z <= i1.z; ++z)
      for (int y = i0.y; y <= i1.y; ++y)
        for (int x = i0.x; x <= i1.x; ++x)
          if (triangleOverlapsBox(glm::dvec3(x, y, z) + 0.5, glm::dvec3(0.5), a, b, c)) g.set(uint32_t(x), uint32_t(y), uint32_t(z));
  }
  return g;
}

SvoCpu::SvoCpu(std::vector<uint32_t> nodes, uint32_t resolution) : nodes_(std::move(nodes)), res_(resolution) {
  while ((1u << depth_) < res_) ++depth_;
}

SvoCpu SvoCpu::fromDense(const DenseVoxelGrid& grid) {
  uint32_t res = grid.resolution(), depth = 0;
  while ((1u << depth) < res) ++depth;
  std::vector<uint32_t> nodes(8, 0);  // group 0: the root (node 0) and 7 unused slots
  // Recursive build in breadth order is not needed for equality of the structure's meaning; a
  // depth-first build keeps the code short.
  std::function<bool(uint32_t, uint32_t, glm::uvec3)> build = [&](uint32_t node, uint32_t level, glm::uvec3 lo) -> bool {
    uint32_t size = res >> level;
    if (level == depth) {
      if (!grid.get(lo.x, lo.y, lo.z)) return false;
      nodes[node] = DYNGI_SVO_FLAG;
      return true;
    }
    bool any = false;
    for (uint32_t z = lo.z; z < lo.z + size && !any; ++z)
      for (uint32_t y = lo.y; y < lo.y + size && !any; ++y)
        for (uint32_t x = lo.x; x < lo.x + size && !any; ++x) any = grid.get(x, y, z);
    if (!any) return false;
    uint32_t g = uint32_t(nodes.size() / 8);
    nodes.resize(nodes.size() + 8, 0);
    nodes[node] = DYNGI_SVO_FLAG | g;
    uint32_t half = size / 2;
    for (uint32_t c = 0; c < 8; ++c)
      build(8 * g + c, level + 1, lo + glm::uvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1) * half);
    return true;
  };
  build(0, 0, glm::uvec3(0));
  return SvoCpu(std::move(nodes), res);
}

bool SvoCpu::occluded(const glm::dvec3& a, const glm::dvec3& b, double eps, uint32_t* stepsOut) const {
  uint32_t steps = 0;
  auto done = [&](bool r) {
    if (stepsOut) *stepsOut = steps;
    return r;
  };
  if (nodes_.empty()) return done(false);
  glm::dvec3 d = b - a;
  double len = glm::length(d);
  if (len <= 2.0 * eps) return done(false);
  glm::dvec3 dir = d / len;
  const double R = double(res_);
  double t = eps, tEnd = len - eps;
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0.0) {
      if (a[i] < 0.0 || a[i] > R) return done(false);
      continue;
    }
    double t0 = (0.0 - a[i]) / dir[i], t1 = (R - a[i]) / dir[i];
    t = std::max(t, std::min(t0, t1));
    tEnd = std::min(tEnd, std::max(t0, t1));
  }
  for (int iter = 0; iter < 1 << 20 && t < tEnd; ++iter) {
    ++steps;
    glm::dvec3 p = a + dir * t;
    uint32_t node = 0;
    glm::dvec3 lo(0.0);
    double size = R;
    for (uint32_t level = 0;; ++level) {
      uint32_t w = nodes_[node];
      if (!(w & DYNGI_SVO_FLAG)) break;
      if (level == depth_) return done(true);
      uint32_t g = w & DYNGI_SVO_GROUP_MASK;
      if (g == 0) return done(true);
      size *= 0.5;
      glm::dvec3 mid = lo + size;
      uint32_t c = 0;
      for (int i = 0; i < 3; ++i)
        if (p[i] > mid[i] || (p[i] == mid[i] && dir[i] >= 0.0)) c |= 1u << i, lo[i] += size;
      node = 8 * g + c;
    }
    double tExit = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i)
      if (dir[i] != 0.0) tExit = std::min(tExit, ((dir[i] > 0.0 ? lo[i] + size : lo[i]) - a[i]) / dir[i]);
    // In double the exit point lands on (or within rounding of) the face; the tie rule then picks the
    // next cell. Guard against a stall with the smallest step that changes t.
    t = tExit > t ? tExit : std::nextafter(t, std::numeric_limits<double>::infinity());
  }
  return done(false);
}

DenseVoxelGrid SvoCpu::leaves() const {
  DenseVoxelGrid g(res_);
  if (nodes_.empty()) return g;
  std::function<void(uint32_t, uint32_t, glm::uvec3)> walk = [&](uint32_t node, uint32_t level, glm::uvec3 lo) {
    uint32_t w = nodes_[node];
    if (!(w & DYNGI_SVO_FLAG)) return;
    if (level == depth_) {
      g.set(lo.x, lo.y, lo.z);
      return;
    }
    uint32_t gr = w & DYNGI_SVO_GROUP_MASK;
    uint32_t half = res_ >> (level + 1);
    if (gr == 0) {  // overflowed node: everything below counts as occupied
      for (uint32_t z = 0; z < 2 * half; ++z)
        for (uint32_t y = 0; y < 2 * half; ++y)
          for (uint32_t x = 0; x < 2 * half; ++x) g.set(lo.x + x, lo.y + y, lo.z + z);
      return;
    }
    for (uint32_t c = 0; c < 8; ++c) walk(8 * gr + c, level + 1, lo + glm::uvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1) * half);
  };
  walk(0, 0, glm::uvec3(0));
  return g;
}

}  // namespace dyngi::gi
