#pragma once
// Which entity a screen pixel shows: a ray from the camera through the pixel against every mesh
// instance's triangles (world transforms, skinned meshes as last deformed). Brute force with a bounding
// box test per instance: for a click, not for a frame's worth of rays.
#include <optional>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::scene {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

struct PickHit {
  ecs::Entity entity{};
  float distance = 0;   // along the ray, world units
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};  // the triangle's, facing the ray
};

// The ray through pixel (x, y) (pixels, top left 0,0; pixel centres at +0.5) of a width x height view
// with this view-projection (Vulkan clip space: depth 0..1, y down on screen).
Ray pixelRay(const glm::mat4& viewProj, uint32_t width, uint32_t height, double x, double y);

// The closest mesh instance the ray hits, if any; an alpha-masked material's cut-outs are passed
// through (scene/alpha_cut.h). Degenerate and non-finite triangles never hit.
std::optional<PickHit> pickClosest(const ecs::World& world, const AssetStore& assets, const Ray& ray);

}  // namespace dyngi::scene
