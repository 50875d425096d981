#include "dyngi/engine/scene/picking.h"

#include <cmath>
#include <limits>

#include "dyngi/engine/scene/alpha_cut.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {
namespace {

// Slab test: the ray's entry distance into the box, or +inf when it misses.
float rayBoxEntry(const Ray& r, const Aabb& b) {
  float t0 = 0.0f, t1 = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / r.direction[a];  // +-inf for an axis-parallel ray: the comparisons still hold
    float tn = (b.min[a] - r.origin[a]) * inv, tf = (b.max[a] - r.origin[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    if (!(tn <= t1 && tf >= t0)) return std::numeric_limits<float>::infinity();  // NaN-safe
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  return t0;
}

// Moeller-Trumbore; the hit distance or +inf, and the barycentrics of b and c.
float rayTriangle(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float& u, float& v) {
  const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (!(std::abs(det) > 1e-12f)) return std::numeric_limits<float>::infinity();
  const float inv = 1.0f / det;
  const glm::vec3 s = o - a;
  u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::numeric_limits<float>::infinity();
  const glm::vec3 q = glm::cross(s, e1);
  v = glm::dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::numeric_limits<float>::infinity();
  const float t = glm::dot(e2, q) * inv;
  return t > 0.0f ? t : std::numeric_limits<float>::infinity();
}

}  // namespace

Ray pixelRay(const glm::mat4& viewProj, uint32_t width, uint32_t height, double x, double y) {
  const glm::mat4 inv = glm::inverse(viewProj);
  const float nx = float(2.0 * x / double(width) - 1.0), ny = float(2.0 * y / double(height) - 1.0);
  glm::vec4 nearP = inv * glm::vec4(nx, ny, 0.0f, 1.0f), farP = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  nearP /= nearP.w;
  farP /= farP.w;
  Ray r;
  r.origin = glm::vec3(nearP);
  r.direction = glm::normalize(glm::vec3(farP) - glm::vec3(nearP));
  return r;
}

std::optional<PickHit> pickClosest(const ecs::World& world, const AssetStore& assets, const Ray& ray) {
  std::optional<PickHit> best;
  float bestT = std::numeric_limits<float>::infinity();
  world.each<MeshInstance, WorldTransform>([&](ecs::Entity e, const MeshInstance& mi, const WorldTransform& wt) {
    if (mi.mesh >= assets.meshCount()) return;
    const MeshData& mesh = assets.mesh(mi.mesh);
    if (!mesh.usable || !mesh.bounds.valid()) return;
    if (!(rayBoxEntry(ray, mesh.bounds.transformed(wt.matrix)) < bestT)) return;
    // A masked material's cut-outs let the ray through, as they do the renderer's and Embree's.
    const Material* material = world.tryGet<Material>(e);
    const AlphaCut cut = material ? AlphaCut::of(*material) : AlphaCut{};
    // In the mesh's own space: one inverse per instance instead of a transform per vertex. Distances
    // along the local ray are world distances because the direction is not renormalized.
    const glm::mat4 inv = glm::inverse(wt.matrix);
    const glm::vec3 o = glm::vec3(inv * glm::vec4(ray.origin, 1.0f)), d = glm::vec3(inv * glm::vec4(ray.direction, 0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const uint32_t ia = mesh.indices[i], ib = mesh.indices[i + 1], ic = mesh.indices[i + 2];
      if (ia >= mesh.positions.size() || ib >= mesh.positions.size() || ic >= mesh.positions.size()) continue;
      const glm::vec3 &a = mesh.positions[ia], &b = mesh.positions[ib], &c = mesh.positions[ic];
      float u = 0.0f, v = 0.0f;
      const float t = rayTriangle(o, d, a, b, c, u, v);
      if (t < bestT && !cut.cuts(assets, mesh, i / 3, u, v)) {
        bestT = t;
        PickHit h;
        h.entity = e;
        h.distance = t;
        h.position = ray.origin + t * ray.direction;
        glm::vec3 n = glm::normalize(glm::transpose(glm::mat3(inv)) * glm::cross(b - a, c - a));
        if (glm::dot(n, ray.direction) > 0.0f) n = -n;
        h.normal = n;
        best = h;
      }
    }
  });
  return best;
}

}  // namespace dyngi::scene
