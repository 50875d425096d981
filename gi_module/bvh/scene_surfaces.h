#pragma once
// What a ray hit, as a shading point: position, geometric and shading normals facing the ray, diffuse
// albedo (base colour x texture x (1 - metallic)) and emission. Shared by the path tracer and the VPL
// shooter so both read materials exactly as the rasterizer does.
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/snapshot.h"
#include "dyngi/gi/bvh.h"

namespace dyngi::gi {

struct SurfaceHit {
  glm::vec3 position, geometricNormal, shadingNormal;
  glm::vec3 diffuseAlbedo;
  glm::vec3 emission;
  ecs::Entity entity;
};

class SceneSurfaces {
 public:
  SceneSurfaces(const render::RenderSnapshot& snapshot, const scene::AssetStore& assets);
  // False when the hit's entity is not among the snapshot's draws.
  bool at(const RayHit& hit, const glm::vec3& origin, const glm::vec3& dir, SurfaceHit& out) const;
  float sceneScale() const { return sceneScale_; }  // diagonal of the scene bounds (for ray offsets)

 private:
  glm::vec3 texel(scene::TextureId id, glm::vec2 uv) const;
  const render::RenderSnapshot& snap_;
  const scene::AssetStore& assets_;
  std::unordered_map<ecs::Entity, size_t> drawOf_;
  // Per draw: the inverse transpose of its model matrix, made once here instead of at every hit (at()
  // held 28 percent of the path tracer's samples under ASan while it inverted it per hit).
  std::vector<glm::mat3> normalMatrices_;
  float sceneScale_ = 1.0f;
};

}  // namespace dyngi::gi
