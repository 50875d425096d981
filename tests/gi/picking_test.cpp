// Picking (engine/scene/picking.h) against Embree's closest hit on the same world, and the sample's
// contract: a click at an object's projected centre selects that entity.
#include <gtest/gtest.h>

#include <random>

#include "support/report.h"
#include "dyngi/engine/render/frame_uniforms.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/picking.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh.h"
#include "scenes/builtin_scenes.h"
#include "support/fence_scene.h"

using namespace dyngi;

namespace {
ecs::Entity named(const ecs::World& w, const std::string& name) {
  ecs::Entity found{};
  w.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value == name) found = e;
  });
  return found;
}
}  // namespace

TEST(Picking, EveryPixelPicksWhatEmbreeHits) {
  ecs::World world;
  scene::AssetStore assets;
  sample::buildBuiltinScene("cornell", world, assets);
  gi::EmbreeScene bvh;
  bvh.sync(world, assets, 0);
  constexpr uint32_t kW = 96, kH = 64;
  const render::RenderSnapshot snap = render::extractSnapshot(world, assets, 0);
  const glm::mat4 viewProj = render::cameraUniforms(snap.camera, kW, kH).viewProj;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  int hits = 0, misses = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const scene::Ray r = scene::pixelRay(viewProj, kW, kH, x + jitter(rng), y + jitter(rng));
      const auto pick = scene::pickClosest(world, assets, r);
      const gi::RayHit ref = bvh.intersect(r.origin, r.direction, 0.0f, 1e30f);
      ASSERT_EQ(pick.has_value(), ref.hit) << x << "," << y;
      if (!ref.hit) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_EQ(pick->entity, ref.entity) << x << "," << y;
      EXPECT_NEAR(pick->distance, ref.t, 1e-4f * ref.t) << x << "," << y;
      EXPECT_LT(glm::dot(pick->normal, r.direction), 0.0f) << "the normal faces the ray";
    }
  EXPECT_GT(hits, int(kW * kH / 2)) << "the camera looks into the room";
  EXPECT_GT(misses, 0) << "and past its open side";
}

TEST(Picking, AClickAtAnObjectsProjectedCentreSelectsIt) {
  ecs::World world;
  scene::AssetStore assets;
  sample::buildBuiltinScene("cornell", world, assets);
  constexpr uint32_t kW = 640, kH = 480;
  const render::RenderSnapshot snap = render::extractSnapshot(world, assets, 0);
  const glm::mat4 viewProj = render::cameraUniforms(snap.camera, kW, kH).viewProj;
  for (const char* name : {"short_box", "tall_box", "back_wall", "floor"}) {
    const ecs::Entity e = named(world, name);
    ASSERT_FALSE(e.isNull()) << name;
    const scene::Aabb box = assets.mesh(world.get<scene::MeshInstance>(e).mesh).bounds.transformed(world.get<scene::WorldTransform>(e).matrix);
    glm::vec3 centre = box.center();
    // The floor's and the back wall's centres are behind the boxes: a point of theirs in view instead.
    if (std::string(name) == "floor") centre.z = 0.8f;
    if (std::string(name) == "back_wall") centre = {0.5f, 1.6f, -1.0f};
    glm::vec4 clip = viewProj * glm::vec4(centre, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const double px = (ndc.x * 0.5 + 0.5) * kW, py = (ndc.y * 0.5 + 0.5) * kH;
    const auto pick = scene::pickClosest(world, assets, scene::pixelRay(viewProj, kW, kH, px, py));
    ASSERT_TRUE(pick.has_value()) << name;
    EXPECT_EQ(pick->entity, e) << name << " at pixel " << px << "," << py;
  }
}

TEST(Picking, DegenerateAndNonFiniteTrianglesNeverHit) {
  ecs::World world;
  scene::AssetStore assets;
  scene::MeshData m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {nan, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.indices = {0, 1, 2, /* collinear */ 3, 4, 5 /* NaN */, 0, 1, 99 /* out of range */};
  m.computeBounds();
  const ecs::Entity e = world.create();
  world.add(e, scene::WorldTransform{glm::mat4(1.0f)});
  world.add(e, scene::MeshInstance{assets.addMesh(std::move(m)), true});
  scene::Ray r;
  r.origin = {0.5f, 0.0f, 1.0f};
  r.direction = {0.0f, 0.0f, -1.0f};
  EXPECT_FALSE(scene::pickClosest(world, assets, r).has_value());
}

// A fence whose left half its base colour's alpha cuts away (alphaMode MASK): a click there picks the
// floor behind it, as Embree (its alpha filter) and the G-buffer see it; on the solid half, the fence.
TEST(Picking, AlphaCutOutsArePickedThroughAsEmbreeSeesThem) {
  ecs::World world;
  scene::AssetStore assets;
  const test::FenceScene fence = test::floorUnderAFence(world, assets);
  scene::TransformSystem().run(world, {});
  gi::EmbreeScene bvh;
  bvh.sync(world, assets, 0);
  constexpr uint32_t kW = 96, kH = 64;
  const render::RenderSnapshot snap = render::extractSnapshot(world, assets, 0);
  const glm::mat4 viewProj = render::cameraUniforms(snap.camera, kW, kH).viewProj;
  int onFence = 0, throughTheCut = 0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const scene::Ray r = scene::pixelRay(viewProj, kW, kH, x + 0.5, y + 0.5);
      const auto pick = scene::pickClosest(world, assets, r);
      const gi::RayHit ref = bvh.intersect(r.origin, r.direction, 0.0f, 1e30f);
      ASSERT_EQ(pick.has_value(), ref.hit) << x << "," << y;
      if (!ref.hit) continue;
      EXPECT_EQ(pick->entity, ref.entity) << x << "," << y;
      EXPECT_NEAR(pick->distance, ref.t, 1e-4f * ref.t) << x << "," << y;
      onFence += pick->entity == fence.fence;
      // The ray crosses the fence's plane over its cut half on the way to what it picked.
      const float tPlane = (test::kFenceHeight - r.origin.y) / r.direction.y;
      const glm::vec3 q = r.origin + tPlane * r.direction;
      const bool overCut = tPlane > 0.0f && tPlane < pick->distance && q.x < -0.05f && q.x > -1.0f && std::abs(q.z) < 1.0f;
      if (overCut) {
        ++throughTheCut;
        EXPECT_EQ(pick->entity, fence.floor) << x << "," << y;
      }
    }
  dyngi::test::report("fence picked at %d pixels; %d pixels picked the floor through the cut half\n", onFence, throughTheCut);
  EXPECT_GT(onFence, 200);
  EXPECT_GT(throughTheCut, 50);
}
