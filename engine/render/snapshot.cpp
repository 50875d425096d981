#include "dyngi/engine/render/snapshot.h"

#include <algorithm>
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

RenderSnapshot extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame) {
  RenderSnapshot s;
  extractSnapshot(world, assets, frame, s);
  return s;
}

void extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame, RenderSnapshot& into) {
  using namespace scene;
  std::vector<DrawItem> draws = std::move(into.draws);
  std::vector<LightItem> lights = std::move(into.lights);
  draws.clear();
  lights.clear();
  into = RenderSnapshot{};
  into.draws = std::move(draws);
  into.lights = std::move(lights);
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
    if (const Material* m = world.tryGet<Material>(e)) d.material = inContentRange(*m);
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
