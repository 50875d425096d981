#include "dyngi/engine/render/snapshot.h"

#include <algorithm>
#include <bit>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace dyngi::render {

glm::mat4 CameraView::projection(float targetAspect) const {
  if (fixedProjection) return projectionMatrix;
  float a = aspect > 0.0f ? aspect : targetAspect;
  glm::mat4 p = glm::perspectiveRH_ZO(yfov, a, znear, zfar);
  p[1][1] *= -1.0f;  // Vulkan's y points down
  return p;
}

CameraView frameBounds(const scene::Aabb& bounds, float yfov) {
  CameraView c;
  glm::vec3 center = bounds.valid() ? bounds.center() : glm::vec3(0.0f);
  float radius = bounds.valid() ? 0.5f * glm::length(bounds.extent()) : 1.0f;
  radius = std::max(radius, 1e-3f);
  float dist = radius / std::sin(0.5f * yfov) * 1.05f;
  c.position = center + glm::vec3(0.0f, 0.25f * radius, dist);
  c.view = glm::lookAtRH(c.position, center, glm::vec3(0, 1, 0));
  c.yfov = yfov;
  c.znear = std::max(dist - radius * 1.5f, dist * 1e-3f);
  c.zfar = dist + radius * 2.0f;
  return c;
}

uint32_t RenderSnapshot::addMaterial(const scene::Material& m) {
  // A hash of the values that tell materials apart; an equal material added recently shares its index.
  uint32_t h = 2166136261u;
  for (float f : {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.baseColor.a, m.emissive.r, m.emissive.g, m.emissive.b, m.metallic, m.roughness})
    h = (h ^ std::bit_cast<uint32_t>(f)) * 16777619u;
  h = (h ^ m.baseColorTexture ^ (m.emissiveTexture << 8) ^ (m.normalTexture << 16)) * 16777619u;
  h ^= h >> 16, h *= 0x85ebca6bu, h ^= h >> 13, h *= 0xc2b2ae35u, h ^= h >> 16;  // float bits differ high: mix them down
  uint32_t& recent = recentMaterials_[h % recentMaterials_.size()];
  if (recent < materials.size() && materials[recent] == m) return recent;
  recent = uint32_t(materials.size());
  materials.push_back(m);
  return recent;
}

RenderSnapshot extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame) {
  RenderSnapshot s;
  extractSnapshot(world, assets, frame, s);
  return s;
}

void extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame, RenderSnapshot& into) {
  using namespace scene;
  std::vector<DrawItem> draws = std::move(into.draws);
  std::vector<LightItem> lights = std::move(into.lights);
  std::vector<Material> materials = std::move(into.materials);
  draws.clear();
  lights.clear();
  materials.assign(1, Material{});
  into = RenderSnapshot{};
  into.draws = std::move(draws);
  into.lights = std::move(lights);
  into.materials = std::move(materials);
  RenderSnapshot& s = into;
  s.assets = &assets;
  s.frame = frame;
  s.draws.reserve(world.count<MeshInstance>());  // grown by doubling, a large scene's list would be copied
  world.each<MeshInstance, WorldTransform>([&](Entity e, const MeshInstance& mi, const WorldTransform& wt) {
    if (mi.mesh >= assets.meshCount()) return;
    const scene::MeshData& mesh = assets.mesh(mi.mesh);
    const Aabb worldBounds = mesh.bounds.transformed(wt.matrix);
    if (!mesh.usable || (mesh.bounds.valid() && !(withinCoordinateRange(worldBounds.min) && withinCoordinateRange(worldBounds.max)))) {
      ++s.skippedDraws;  // nothing downstream (bounds, voxel volume, light views) may see an infinity
      return;
    }
    DrawItem d;
    d.entity = e;
    d.mesh = mi.mesh;
    d.model = wt.matrix;
    d.castShadows = mi.castShadows;
    // Clamped as the importer and the host API clamp: a component written directly (a system, a script,
    // a host's ECS code) cannot carry a NaN or an overflowing value into lighting.
    if (const Material* m = world.tryGet<Material>(e)) d.material = s.addMaterial(inContentRange(*m));
    s.sceneBounds.extend(worldBounds);
    s.draws.push_back(d);
  });
  // One line when the number of left-out instances changes, not one a frame.
  static std::atomic<uint32_t> lastSkipped{0};
  if (uint32_t before = lastSkipped.exchange(s.skippedDraws); before != s.skippedDraws && s.skippedDraws > 0)
    std::fprintf(stderr, "dyngi: warning: %u mesh instance(s) with non-finite vertices or beyond the coordinate range (1e18) left out of the frame\n",
                 s.skippedDraws);
  world.each<Light, WorldTransform>([&](Entity e, const Light& l, const WorldTransform& wt) {
    LightItem li;
    li.entity = e;
    li.light = inContentRange(l);
    li.position = glm::vec3(wt.matrix[3]);
    glm::vec3 dir = -glm::vec3(wt.matrix[2]);
    float len = glm::length(dir);
    li.direction = len > 0.0f ? dir / len : glm::vec3(0, 0, -1);
    s.lights.push_back(li);
  });
  bool haveCamera = false;
  world.each<ActiveCamera, Camera, WorldTransform>([&](Entity, const ActiveCamera&, const Camera& c, const WorldTransform& wt) {
    if (haveCamera) return;
    haveCamera = true;
    // Cameras look down local -Z; strip scale from the world matrix before inverting.
    glm::mat4 m = wt.matrix;
    for (int i = 0; i < 3; ++i) {
      float len = glm::length(glm::vec3(m[i]));
      if (len > 0.0f) m[i] /= len;
    }
    s.camera.view = glm::inverse(m);
    s.camera.position = glm::vec3(wt.matrix[3]);
    s.camera.yfov = c.yfov;
    s.camera.znear = c.znear;
    s.camera.zfar = c.zfar;
    s.camera.aspect = c.aspect;
  });
  if (!haveCamera) s.camera = frameBounds(s.sceneBounds);
}

}  // namespace dyngi::render
