// The scripted scenes (--animate) build on each other (fox-spot-light-on is fox-and-spot plus a light,
// which is walking-fox plus motion): each must hold one Cornell box, not one per layer (overlapping
// walls and a spot per layer, which the soak and budget runs once measured).
#include <gtest/gtest.h>

#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "scenes/builtin_scenes.h"
#include "support/shared_scenes.h"

using namespace dyngi;

namespace {
struct Census {
  int floors = 0, lights = 0, enabledLights = 0, switches = 0;
};
Census census(const std::string& name) {
  ecs::World w;
  scene::AssetStore assets;
  const std::string err = sample::buildAnimatedScene(name, w, assets, DYNGI_SHARED_SCENES);
  EXPECT_TRUE(err.empty()) << name << ": " << err;
  Census c;
  w.each<scene::Name>([&](ecs::Entity, const scene::Name& n) { c.floors += n.value == "floor"; });
  w.each<scene::Light>([&](ecs::Entity, const scene::Light& l) { ++c.lights, c.enabledLights += l.enabled; });
  w.each<scene::ScriptedLightSwitch>([&](ecs::Entity, const scene::ScriptedLightSwitch&) { ++c.switches; });
  return c;
}
}  // namespace

TEST(ScriptedScenes, EachHoldsOneCornellBox) {
  DYNGI_SHARED_SCENE_OR_SKIP(fox, "Fox.glb");
  for (const char* name : {"static", "moving-spot", "rotating-object", "moving-camera", "walking-fox", "fox-and-spot"}) {
    const Census c = census(name);
    EXPECT_EQ(c.floors, 1) << name;
    EXPECT_EQ(c.lights, 1) << name;
  }
  const Census on = census("fox-spot-light-on");
  EXPECT_EQ(on.floors, 1);
  EXPECT_EQ(on.lights, 2);
  EXPECT_EQ(on.enabledLights, 1) << "the second spot starts off";
  EXPECT_EQ(on.switches, 1);
}

// The second spot switches on at its time and only then (its change tick moves once).
TEST(ScriptedScenes, ALightSwitchFollowsScriptedTime) {
  ecs::World w;
  ecs::Entity e = w.create();
  w.add(e, scene::Light{.enabled = false});
  w.add(e, scene::ScriptedLightSwitch{.onAt = 1.0, .offAt = 2.0});
  scene::ScriptedMotionSystem system;
  auto at = [&](double t) {
    ecs::SystemContext ctx{};
    ctx.time.time = t;
    system.run(w, ctx);
    return w.get<scene::Light>(e).enabled;
  };
  EXPECT_FALSE(at(0.5));
  EXPECT_TRUE(at(1.0));
  EXPECT_TRUE(at(1.9));
  EXPECT_FALSE(at(2.0));
}

// The large-world scene: "street" spans 400 m with the camera inside its bounds (so the directional
// focus applies); "street-near" is the same view holding only the ground and blocks that end within
// StreetLayout::kNearReach of the camera along the street.
TEST(ScriptedScenes, TheStreetAndItsNearCopyShareTheirView) {
  using L = sample::StreetLayout;
  struct Built {
    scene::Aabb bounds;
    int blocks = 0;
    float blocksEndAt = -1e30f;
    glm::vec3 camera{0.0f};
  };
  auto build = [](const char* name) {
    ecs::World w;
    scene::AssetStore assets;
    sample::buildBuiltinScene(name, w, assets);
    Built b;
    w.each<scene::MeshInstance, scene::Transform, scene::Name>([&](ecs::Entity, const scene::MeshInstance& m, const scene::Transform& t, const scene::Name& n) {
      const scene::Aabb local = assets.mesh(m.mesh).bounds;
      const glm::vec3 lo = local.min + t.translation, hi = local.max + t.translation;  // unrotated, unscaled
      b.bounds.extend(lo);
      b.bounds.extend(hi);
      if (n.value.rfind("block_", 0) == 0) ++b.blocks, b.blocksEndAt = std::max(b.blocksEndAt, hi.x);
    });
    w.each<scene::ActiveCamera, scene::Transform>([&](ecs::Entity, const scene::ActiveCamera&, const scene::Transform& t) { b.camera = t.translation; });
    return b;
  };
  const Built street = build("street"), near = build("street-near");
  EXPECT_NEAR(street.bounds.extent().x, 2.0f * L::kHalfLength, 1e-3f);
  EXPECT_GE(street.blocks, 30);
  EXPECT_EQ(street.camera, L::kCamera);
  EXPECT_EQ(near.camera, L::kCamera);
  for (const Built* b : {&street, &near})
    EXPECT_TRUE(glm::all(glm::greaterThan(b->camera, b->bounds.min)) && glm::all(glm::lessThan(b->camera, b->bounds.max))) << "the camera in the scene";
  EXPECT_LE(near.blocksEndAt, L::kCamera.x + L::kNearReach + 1e-3f);
  EXPECT_LE(near.bounds.max.x, L::kCamera.x + L::kNearReach + 1e-3f);
  EXPECT_GE(near.blocks, 2);
  EXPECT_LT(near.blocks, street.blocks / 4);

  // --animate street-flight: the street, its camera flying east at kFlightSpeed, facing east.
  ecs::World w;
  scene::AssetStore assets;
  ASSERT_EQ(sample::buildAnimatedScene("street-flight", w, assets, DYNGI_SHARED_SCENES), "");
  int flights = 0;
  w.each<scene::ActiveCamera, scene::ScriptedMotion, scene::Transform>(
      [&](ecs::Entity, const scene::ActiveCamera&, const scene::ScriptedMotion& m, const scene::Transform& t) {
        ++flights;
        glm::vec3 at;
        glm::quat facing;
        scene::evaluateMotion(m, 2.0, at, facing);
        EXPECT_NEAR(glm::distance(at, L::kCamera + glm::vec3(2.0f * L::kFlightSpeed, 0.0f, 0.0f)), 0.0f, 1e-3f);
        EXPECT_NEAR(glm::abs(glm::dot(facing, t.rotation)), 1.0f, 1e-5f);
      });
  EXPECT_EQ(flights, 1);
}
