#pragma once
// The read-only copy of what the renderer needs from the ECS this frame. Data flows one way:
// ECS -> snapshot -> GPU; nothing in render/ writes back into the world.
#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::render {

struct DrawItem {
  scene::Entity entity;
  scene::MeshId mesh = 0;
  glm::mat4 model{1.0f};
  uint32_t material = 0;  // index into RenderSnapshot::materials
  bool castShadows = true;
};

struct LightItem {
  scene::Entity entity;
  scene::Light light;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world direction the light points along (unit)
};

struct CameraView {
  glm::mat4 view{1.0f};
  glm::vec3 position{0.0f};
  float yfov = 0.8f, znear = 0.05f, zfar = 100.0f;
  float aspect = 0.0f;  // 0: from the render target
  // A host's own projection (gi::GiContext) instead of yfov, znear, zfar and aspect.
  bool fixedProjection = false;
  glm::mat4 projectionMatrix{1.0f};
  glm::mat4 projection(float targetAspect) const;  // Vulkan clip space (y down, depth 0..1)
};

struct RenderSnapshot {
  std::vector<DrawItem> draws;  // one per mesh instance (entity)
  // The draws' materials, each held once where neighbouring draws share one (instances of a prop):
  // [0] is the default material, for a draw without one.
  std::vector<scene::Material> materials{scene::Material{}};
  std::vector<LightItem> lights;
  CameraView camera;
  scene::Aabb sceneBounds;  // of all draws, world space
  uint32_t skippedDraws = 0;  // mesh instances left out: mesh not usable, or world bounds beyond the coordinate range
  const scene::AssetStore* assets = nullptr;
  uint64_t frame = 0;

  const scene::Material& materialOf(const DrawItem& d) const { return materials[d.material]; }
  // The index of `m` in `materials`: an equal one among the last few added, else appended.
  uint32_t addMaterial(const scene::Material& m);

 private:
  std::array<uint32_t, 64> recentMaterials_{};  // by a hash of the material: an index into `materials`
};

// A camera that frames `bounds` from the +Z side (used when the scene has none).
CameraView frameBounds(const scene::Aabb& bounds, float yfov = 0.8f);

RenderSnapshot extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame);
// The same into `into`, keeping its lists' memory: a frame loop that keeps one snapshot does not allocate
// (and fault in) a large scene's draw list again every frame.
void extractSnapshot(const ecs::World& world, const scene::AssetStore& assets, uint64_t frame, RenderSnapshot& into);

}  // namespace dyngi::render
