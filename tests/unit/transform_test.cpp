#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"

using namespace dyngi;
using namespace dyngi::scene;

namespace {
void expectNear(const glm::mat4& a, const glm::mat4& b, float eps = 1e-5f) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], eps) << "at [" << c << "][" << r << "]";
}
}  // namespace

TEST(TransformSystem, PropagatesHierarchyAndOnlyTouchesChangedSubtrees) {
  ecs::World w;
  ecs::Scheduler s;
  auto& sys = static_cast<TransformSystem&>(s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>()));
  Entity root = w.create(), child = w.create(), grandchild = w.create(), other = w.create();
  Transform rt;
  rt.translation = {1, 0, 0};
  rt.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 1, 0));
  w.add(root, rt);
  Transform ct;
  ct.translation = {0, 0, -2};
  ct.scale = glm::vec3(2.0f);
  ct.parent = root;
  w.add(child, ct);
  Transform gt;
  gt.translation = {1, 1, 1};
  gt.parent = child;
  w.add(grandchild, gt);
  w.add(other, Transform{});
  s.runFrame(w, {});
  // Reference: explicit matrix products.
  glm::mat4 rootM = glm::translate(glm::mat4(1), {1, 0, 0}) * glm::rotate(glm::mat4(1), glm::radians(90.0f), {0, 1, 0});
  glm::mat4 childM = rootM * glm::translate(glm::mat4(1), {0, 0, -2}) * glm::scale(glm::mat4(1), glm::vec3(2));
  glm::mat4 grandM = childM * glm::translate(glm::mat4(1), {1, 1, 1});
  expectNear(w.get<WorldTransform>(root).matrix, rootM);
  expectNear(w.get<WorldTransform>(child).matrix, childM);
  expectNear(w.get<WorldTransform>(grandchild).matrix, grandM);
  EXPECT_EQ(sys.updatedLastRun(), 4u);

  // Move the root only: its subtree's world transforms change, `other` is not touched.
  ecs::Tick before = w.tick();
  w.advanceTick();
  w.write<Transform>(root).translation = {0, 5, 0};
  s.runFrame(w, {});
  EXPECT_EQ(sys.updatedLastRun(), 3u);
  auto moved = w.changedSince<WorldTransform>(before);
  EXPECT_EQ(moved.size(), 3u);
  for (Entity e : moved) EXPECT_NE(e, other);
  EXPECT_NEAR(w.get<WorldTransform>(grandchild).matrix[3].y, 5.0f + 1.0f * 2.0f, 1e-5f);

  // No change: nothing updated, no WorldTransform ticks.
  before = w.tick();
  s.runFrame(w, {});
  EXPECT_EQ(sys.updatedLastRun(), 0u);
  EXPECT_TRUE(w.changedSince<WorldTransform>(before).empty());
}

TEST(TransformSystem, NonFiniteTransformKeepsLastGoodMatrix) {
  ecs::World w;
  ecs::Scheduler s;
  auto& sys = static_cast<TransformSystem&>(s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>()));
  Entity e = w.create();
  Transform t;
  t.translation = {1, 2, 3};
  w.add(e, t);
  s.runFrame(w, {});
  glm::mat4 good = w.get<WorldTransform>(e).matrix;
  w.write<Transform>(e).translation.x = std::numeric_limits<float>::quiet_NaN();
  s.runFrame(w, {});
  expectNear(w.get<WorldTransform>(e).matrix, good, 0.0f);
  EXPECT_EQ(sys.rejectedNonFinite(), 1u);
  // Finite but beyond the engine's coordinate range (a runaway object): kept back the same way, so no
  // bounds or squared distance downstream overflows.
  w.write<Transform>(e).translation = {1e19f, 0, 0};
  s.runFrame(w, {});
  expectNear(w.get<WorldTransform>(e).matrix, good, 0.0f);
  w.write<Transform>(e).scale = glm::vec3(1e10f);
  w.write<Transform>(e).translation = {1, 2, 3};
  Entity child = w.create();
  w.add(child, Transform{.translation = {1e9f, 0, 0}, .parent = e});  // 1e10 x 1e9: the product leaves the range
  s.runFrame(w, {});
  EXPECT_TRUE(withinCoordinateRange(w.get<WorldTransform>(e).matrix)) << "1e10 scale alone is in range";
  EXPECT_FALSE(w.has<WorldTransform>(child)) << "never given a world matrix beyond the range";
  EXPECT_EQ(sys.rejectedNonFinite(), 3u);
}

TEST(ScriptedMotion, IsAPureFunctionOfTime) {
  ScriptedMotion m;
  m.origin = {1, 0, 0};
  m.orbitRadius = 0.5f;
  m.orbitSpeed = 1.0f;
  m.spinSpeed = 2.0f;
  m.path = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}};
  m.pathSpeed = 0.3f;
  glm::vec3 a, b;
  glm::quat qa, qb;
  evaluateMotion(m, 1.2345, a, qa);
  evaluateMotion(m, 7.0, b, qb);
  evaluateMotion(m, 1.2345, b, qb);
  EXPECT_EQ(a, b);
  EXPECT_EQ(qa, qb);
  // An orbit alone stays on its circle.
  ScriptedMotion orbit;
  orbit.orbitRadius = 2.0f;
  orbit.orbitSpeed = 0.7f;
  for (double t : {0.0, 0.5, 3.0, 10.0}) {
    evaluateMotion(orbit, t, a, qa);
    EXPECT_NEAR(glm::length(a), 2.0f, 1e-5f);
    EXPECT_NEAR(a.y, 0.0f, 1e-6f);
  }
  // A path at speed v reaches its second point after |p1 - p0| / v seconds.
  ScriptedMotion path;
  path.path = {{0, 0, 0}, {2, 0, 0}, {2, 0, 2}};
  path.pathSpeed = 1.0f;
  evaluateMotion(path, 2.0, a, qa);
  EXPECT_NEAR(glm::distance(a, glm::vec3(2, 0, 0)), 0.0f, 1e-5f);
  evaluateMotion(path, 3.0, a, qa);
  EXPECT_NEAR(glm::distance(a, glm::vec3(2, 0, 1)), 0.0f, 1e-5f);
}
