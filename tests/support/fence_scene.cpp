#include "support/fence_scene.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "dyngi/engine/scene/components.h"

namespace dyngi::test {

FenceScene floorUnderAFence(ecs::World& w, scene::AssetStore& a) {
  FenceScene s;
  s.floor = w.create();
  w.add(s.floor, scene::Transform{});
  w.add(s.floor, scene::MeshInstance{a.addMesh(scene::makeQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4})), true});
  w.add(s.floor, scene::Material{.baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f)});
  scene::TextureData t;
  t.width = t.height = 8;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) t.rgba8.insert(t.rgba8.end(), {200, 120, 60, uint8_t(x < 4 ? 0 : 255)});
  s.fence = w.create();
  w.add(s.fence, scene::Transform{});
  // Both faces: the quad's uv u runs along +x.
  w.add(s.fence, scene::MeshInstance{a.addMesh(scene::makeQuad({-1, kFenceHeight, 1}, {2, 0, 0}, {0, 0, -2})), true});
  w.add(s.fence, scene::Material{.baseColorTexture = a.addTexture(t), .alphaMask = true, .alphaCutoff = 0.5f});
  s.sun = w.create();
  scene::Transform st;
  st.rotation = glm::quatLookAtRH(glm::normalize(kFenceSunDirection), glm::vec3(0, 1, 0));
  w.add(s.sun, st);
  w.add(s.sun, scene::Light{.type = scene::LightType::Directional, .intensity = 2.0f});
  s.camera = w.create();
  scene::Transform ct;
  ct.translation = {3.5f, 3.5f, 0.5f};
  ct.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(-3.5f, -3.5f, -0.5f)), glm::vec3(0, 1, 0));
  w.add(s.camera, ct);
  w.add(s.camera, scene::Camera{.yfov = 1.0f});
  w.add(s.camera, scene::ActiveCamera{});
  return s;
}

Under underTheFence(const glm::vec3& p) {
  const glm::vec3 toSun = -glm::normalize(kFenceSunDirection);
  const glm::vec3 q = p + toSun * (kFenceHeight / toSun.y);
  if (std::abs(q.x) > 1.0f || std::abs(q.z) > 1.0f) return Under::Open;
  return q.x < 0.0f ? Under::Hole : Under::Solid;
}

}  // namespace dyngi::test
