#pragma once
// World-space triangle soup of a world (for brute-force oracles) and a Moller-Trumbore ray test.
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/scene/assets.h"

namespace dyngi::test {

struct WorldTriangle {
  glm::vec3 a, b, c;
  ecs::Entity entity;
  uint32_t primitive;
};

std::vector<WorldTriangle> worldTriangles(const ecs::World& world, const scene::AssetStore& assets);

// Closest hit distance along o + t d (d need not be unit) in (tmin, tmax), or -1.
float bruteForceHit(const std::vector<WorldTriangle>& tris, const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                    size_t* which = nullptr);

}  // namespace dyngi::test
