#include "dyngi/engine/scene/transform_system.h"

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <unordered_map>
#include <unordered_set>

#include "dyngi/engine/scene/components.h"

namespace dyngi::scene {

glm::mat4 Transform::matrix() const {
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translation, 1.0f);
  return m;
}

bool isFinite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

bool withinCoordinateRange(const glm::vec3& p) {
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(p[i]) <= kMaxCoordinate)) return false;  // also false for NaN
  return true;
}

bool withinCoordinateRange(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::abs(m[c][r]) <= kMaxCoordinate)) return false;
  return true;
}

void TransformSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  updatedLastRun_ = 0;
  std::vector<Entity> changed = world.changedSince<Transform>(ctx.lastRun);
  if (changed.empty()) return;

  // Children lists, only built when something changed.
  std::unordered_map<uint32_t, std::vector<Entity>> children;
  world.each<Transform>([&](Entity e, const Transform& t) {
    if (!t.parent.isNull()) children[t.parent.index].push_back(e);
  });

  std::unordered_set<Entity> done;
  // Recompute e's subtree. `depth` guards against parent cycles made at run time.
  auto update = [&](auto& self, Entity e, int depth) -> void {
    if (depth > 256 || !done.insert(e).second) return;
    const Transform& t = world.get<Transform>(e);
    glm::mat4 parentWorld(1.0f);
    if (!t.parent.isNull() && world.alive(t.parent)) {
      if (const auto* pw = world.tryGet<WorldTransform>(t.parent)) parentWorld = pw->matrix;
    }
    glm::mat4 m = parentWorld * t.matrix();
    if (!withinCoordinateRange(m)) {
      if (++rejectedNonFinite_ <= 8)
        std::fprintf(stderr, "dyngi: warning: entity %u has a non-finite transform or one beyond the coordinate range "
                     "(1e18); keeping its last good one\n", e.index);
      return;  // children keep their last world too
    }
    const WorldTransform* current = world.tryGet<WorldTransform>(e);
    if (!current) world.add(e, WorldTransform{m}), ++updatedLastRun_;
    else if (current->matrix != m) world.write<WorldTransform>(e).matrix = m, ++updatedLastRun_;
    if (auto it = children.find(e.index); it != children.end())
      for (Entity c : it->second) self(self, c, depth + 1);
  };

  // Update from the top: an entity whose ancestor also changed is reached through that ancestor,
  // which must run first so the child sees the new parent matrix.
  for (Entity e : changed) {
    Entity top = e;
    int guard = 0;
    for (Entity p = world.get<Transform>(e).parent; !p.isNull() && world.alive(p) && world.has<Transform>(p) && guard < 256;
         p = world.get<Transform>(p).parent, ++guard) {
      if (world.poolIfAny<Transform>()->changedTick(p) > ctx.lastRun) top = p;
    }
    update(update, top, 0);
  }
}

}  // namespace dyngi::scene
