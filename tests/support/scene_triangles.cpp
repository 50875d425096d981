#include "support/scene_triangles.h"

#include <cmath>

#include "dyngi/engine/scene/components.h"

namespace dyngi::test {

std::vector<WorldTriangle> worldTriangles(const ecs::World& world, const scene::AssetStore& assets) {
  std::vector<WorldTriangle> out;
  world.each<scene::MeshInstance, scene::WorldTransform>([&](ecs::Entity e, const scene::MeshInstance& mi, const scene::WorldTransform& wt) {
    const scene::MeshData& m = assets.mesh(mi.mesh);
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      auto w = [&](uint32_t i) { return glm::vec3(wt.matrix * glm::vec4(m.positions[i], 1.0f)); };
      out.push_back({w(m.indices[t]), w(m.indices[t + 1]), w(m.indices[t + 2]), e, uint32_t(t / 3)});
    }
  });
  return out;
}

float bruteForceHit(const std::vector<WorldTriangle>& tris, const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, size_t* which) {
  // Double precision so the oracle is not the weaker party.
  float best = -1.0f;
  double bestT = double(tmax);
  glm::dvec3 O(o), D(d);
  for (size_t i = 0; i < tris.size(); ++i) {
    glm::dvec3 A(tris[i].a), B(tris[i].b), C(tris[i].c);
    glm::dvec3 e1 = B - A, e2 = C - A, p = glm::cross(D, e2);
    double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-18) continue;
    double inv = 1.0 / det;
    glm::dvec3 s = O - A;
    double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) continue;
    glm::dvec3 q = glm::cross(s, e1);
    double v = glm::dot(D, q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    double t = glm::dot(e2, q) * inv;
    if (t > double(tmin) && t < bestT) {
      bestT = t;
      best = float(t);
      if (which) *which = i;
    }
  }
  return best;
}

}  // namespace dyngi::test
