// The Embree scene against a brute-force ray/triangle oracle: static, after moving instances, after
// adding/removing entities, and after a skinned deformation + refit.
#include <gtest/gtest.h>

#include "support/shared_scenes.h"

#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/gi/bvh_sync.h"
#include "scenes/builtin_scenes.h"
#include "support/scene_triangles.h"
#include "gi/skinned_bar_room.h"

using namespace dyngi;
using namespace dyngi::scene;

namespace {

struct Agreement {
  int rays = 0, hits = 0, mismatches = 0;
  double worstRel = 0;
};

// Random rays from points inside `bounds` in random directions.
Agreement compare(const gi::EmbreeScene& bvh, const ecs::World& w, const AssetStore& assets, const Aabb& bounds, int count, uint32_t seed) {
  auto tris = test::worldTriangles(w, assets);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  Agreement a;
  for (int i = 0; i < count; ++i) {
    glm::vec3 o = bounds.min + glm::vec3(U(rng), U(rng), U(rng)) * bounds.extent();
    glm::vec3 d = glm::normalize(glm::vec3(U(rng) - 0.5f, U(rng) - 0.5f, U(rng) - 0.5f));
    float ref = test::bruteForceHit(tris, o, d, 0.0f, 1e30f);
    gi::RayHit h = bvh.intersect(o, d, 0.0f, 1e30f);
    ++a.rays;
    if (h.hit != (ref > 0.0f)) {
      ++a.mismatches;
      continue;
    }
    if (!h.hit) continue;
    ++a.hits;
    // Relative to the distance, floored at 1 cm: float positions carry ~1e-7 absolute error, which
    // is not a relative 1e-4 on rays that start a hair from a wall.
    double rel = std::abs(double(h.t) - ref) / std::max(double(ref), 0.01);
    a.worstRel = std::max(a.worstRel, rel);
    // Occlusion of the segment to just before / just past the hit agrees too.
    EXPECT_FALSE(bvh.occluded(gi::Segment{o, o + d * (ref * 0.999f)}, 0.0f));
    EXPECT_TRUE(bvh.occluded(gi::Segment{o, o + d * (ref * 1.001f + 1e-3f)}, 0.0f));
  }
  return a;
}

void expectAgreement(const Agreement& a) {
  EXPECT_EQ(a.mismatches, 0) << "hit/miss disagreements out of " << a.rays;
  EXPECT_GT(a.hits, a.rays / 2);
  EXPECT_LT(a.worstRel, 1e-4);
}

Aabb roomBounds() {
  Aabb b;
  b.extend(glm::vec3(-0.98f, 0.02f, -0.98f));
  b.extend(glm::vec3(0.98f, 1.98f, 0.98f));
  return b;
}

}  // namespace

TEST(EmbreeScene, StaticCornellMatchesBruteForce) {
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  gi::EmbreeScene bvh;
  const auto& st = bvh.sync(w, assets, 0);
  EXPECT_EQ(st.instances, 7u);
  EXPECT_EQ(st.meshesRebuilt, 7u);
  expectAgreement(compare(bvh, w, assets, roomBounds(), 4000, 1));
  // Hits name the entity and primitive.
  gi::RayHit h = bvh.intersect({0, 1.9f, 0.9f}, {0, -1, 0}, 0, 10);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 1.9f, 1e-5f);
  EXPECT_EQ(w.get<Name>(h.entity).value, "floor");
  EXPECT_LT(h.primitive, 2u);
}

TEST(EmbreeScene, MovingInstancesUpdateOnlyTransforms) {
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell-dynamic", w, assets);
  ecs::Scheduler s;
  s.add(ecs::Phase::Update, std::make_unique<ScriptedMotionSystem>());
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  gi::EmbreeScene bvh;
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  s.runFrame(w, {});
  for (int f = 1; f <= 5; ++f) {
    s.runFrame(w, ecs::FrameTime{0.25, 0.25 * f, uint64_t(f)});
    const auto& st = bvh.stats();
    EXPECT_EQ(st.instancesUpdated, 2u) << "the two moving boxes (the light is not geometry)";
    EXPECT_EQ(st.meshesRebuilt, 0u);
    EXPECT_EQ(st.meshesRefit, 0u);
    EXPECT_EQ(st.instancesAdded, 0u);
  }
  expectAgreement(compare(bvh, w, assets, roomBounds(), 3000, 2));
}

TEST(EmbreeScene, EntitiesAddedAndRemovedAtRunTime) {
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  ecs::Tick t = w.tick();
  w.advanceTick();
  Entity ball = w.create();
  Transform bt;
  bt.translation = {0.0f, 1.0f, 0.5f};
  w.add(ball, bt);
  w.add(ball, WorldTransform{bt.matrix()});
  w.add(ball, MeshInstance{assets.addMesh(makeSphere(0.2f, 24, 12)), true});
  Entity floor{};
  w.each<Name>([&](Entity e, const Name& n) { if (n.value == "floor") floor = e; });
  w.destroy(floor);
  const auto& st = bvh.sync(w, assets, t);
  EXPECT_EQ(st.instancesAdded, 1u);
  EXPECT_EQ(st.instancesRemoved, 1u);
  EXPECT_EQ(st.instances, 7u);
  expectAgreement(compare(bvh, w, assets, roomBounds(), 3000, 3));
  gi::RayHit h = bvh.intersect({0, 1.0f, 1.5f}, {0, 0, -1}, 0, 10);
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.entity, ball);
  EXPECT_FALSE(bvh.intersect({0, 0.5f, 0.9f}, {0, -1, 0}, 0, 10).hit) << "the floor is gone";
}

TEST(EmbreeScene, SkinnedFoxRefitMatchesBruteForce) {
  DYNGI_SHARED_SCENE_OR_SKIP(path, "Fox.glb");
  ecs::World w;
  AssetStore assets;
  ImportOptions io;
  io.clip = "Run";
  ASSERT_EQ(importGltf(path, w, assets, nullptr, io), "");
  ecs::Scheduler s;
  s.add(ecs::Phase::Update, std::make_unique<AnimationSystem>());
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  s.add(ecs::Phase::PostUpdate, std::make_unique<SkinningSystem>(assets));
  gi::EmbreeScene bvh;
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  for (int f = 0; f < 12; ++f) s.runFrame(w, ecs::FrameTime{1.0 / 30, f / 30.0, uint64_t(f)});
  EXPECT_EQ(bvh.stats().meshesRefit, 1u);
  EXPECT_EQ(bvh.stats().meshesRebuilt, 0u);
  Aabb b;
  w.each<SkinnedMesh, WorldTransform>([&](Entity, const SkinnedMesh& sm, const WorldTransform& wt) {
    b.extend(assets.mesh(sm.deformed).bounds.transformed(wt.matrix));
  });
  // Rays from a box around the fox, aimed at its middle so many hit.
  auto tris = test::worldTriangles(w, assets);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  int hits = 0, mismatches = 0;
  double worst = 0;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 o = b.center() + (glm::vec3(U(rng), U(rng), U(rng)) - 0.5f) * b.extent() * 3.0f;
    glm::vec3 target = b.min + glm::vec3(U(rng), U(rng), U(rng)) * b.extent();
    glm::vec3 d = glm::normalize(target - o);
    float ref = test::bruteForceHit(tris, o, d, 0.0f, 1e30f);
    gi::RayHit h = bvh.intersect(o, d, 0.0f, 1e30f);
    if (h.hit != (ref > 0)) { ++mismatches; continue; }
    if (h.hit) ++hits, worst = std::max(worst, std::abs(double(h.t) - ref) / ref);
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 600);
  EXPECT_LT(worst, 1e-4);
}

TEST(EmbreeScene, PacketOcclusionEqualsSingleRays) {
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  Aabb r = roomBounds();
  std::vector<gi::Segment> segs(1003);
  for (auto& s : segs) {
    s.from = r.min + glm::vec3(U(rng), U(rng), U(rng)) * r.extent();
    s.to = r.min + glm::vec3(U(rng), U(rng), U(rng)) * r.extent();
  }
  segs[17].to = segs[17].from;  // a degenerate segment is never occluded
  std::vector<uint8_t> packet(segs.size()), stream(segs.size());
  bvh.occluded(segs.data(), segs.size(), packet.data(), 1e-4f, gi::EmbreeScene::BatchMode::Packet8);
  bvh.occluded(segs.data(), segs.size(), stream.data(), 1e-4f, gi::EmbreeScene::BatchMode::Stream);
  int blocked = 0;
  for (size_t i = 0; i < segs.size(); ++i) {
    EXPECT_EQ(packet[i] != 0, bvh.occluded(segs[i])) << i;
    EXPECT_EQ(stream[i], packet[i]) << i;
    blocked += packet[i];
  }
  EXPECT_EQ(packet[17], 0);
  EXPECT_GT(blocked, 50);
  EXPECT_LT(blocked, 950);
}

TEST(EmbreeScene, SkinnedTwoBoneBarRefitsAndMatchesBruteForceAsItBends) {
  // A skinned mesh made in code (no ../shared needed): as it bends, each frame refits its BLAS (no
  // rebuild) and the BVH answers every ray as a brute-force test over the deformed triangles does.
  test::SkinnedBarRoom room({0.4f, 0.0f, 0.0f});
  ASSERT_EQ(room.bar.error, "");
  ecs::World& w = room.world;
  AssetStore& assets = room.assets;
  const test::SkinnedBar& bar = room.bar;
  ecs::Scheduler& s = room.scheduler;
  gi::EmbreeScene bvh;
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  const MeshId deformed = room.deformed;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  w.write<Animator>(bar.animator).loop = false;  // hold the last pose at t = 1 s
  for (int f = 0; f <= 30; ++f) {
    s.runFrame(w, ecs::FrameTime{1.0 / 30, f / 30.0, uint64_t(f)});
    if (f == 0) continue;
    if (f < 30) {  // (t = 1 s holds the last pose: nothing to refit)
      EXPECT_EQ(bvh.stats().meshesRefit, 1u) << "frame " << f;
    }
    EXPECT_EQ(bvh.stats().meshesRebuilt, 0u) << "frame " << f;
    if (f % 10 != 0) continue;
    const Aabb b = assets.mesh(deformed).bounds.transformed(w.get<WorldTransform>(bar.mesh).matrix);
    auto tris = test::worldTriangles(w, assets);
    int hits = 0, mismatches = 0;
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
      glm::vec3 o = b.center() + (glm::vec3(U(rng), U(rng), U(rng)) - 0.5f) * glm::max(b.extent(), glm::vec3(0.3f)) * 2.5f;
      glm::vec3 d = glm::normalize(b.min + glm::vec3(U(rng), U(rng), U(rng)) * b.extent() - o);
      float ref = test::bruteForceHit(tris, o, d, 0.0f, 1e30f);
      gi::RayHit h = bvh.intersect(o, d, 0.0f, 1e30f);
      if (h.hit != (ref > 0)) { ++mismatches; continue; }
      if (h.hit) ++hits, worst = std::max(worst, std::abs(double(h.t) - ref) / std::max(double(ref), 0.01));
    }
    EXPECT_EQ(mismatches, 0) << "frame " << f;
    EXPECT_GT(hits, 1000) << "frame " << f;
    // Folded, the bar's inner faces interpenetrate at the joint: two triangles within a hair of each
    // other may each be the first hit, so the distance agrees to 1e-3 rather than the fox's 1e-4.
    EXPECT_LT(worst, 1e-3) << "frame " << f;
  }
  // After 1 s the upper half lies along -X: the bar's top has come down to the joint's height. (The
  // refit above found a real bug: Embree kept the instance's old bounds at the top level.)
  const Aabb end = assets.mesh(deformed).bounds.transformed(w.get<WorldTransform>(bar.mesh).matrix);
  EXPECT_NEAR(end.min.x, 0.4f - 0.6f, 0.01f);  // the top, 0.6 above the joint, now 0.6 to its -X side
  EXPECT_NEAR(end.max.y, 0.68f, 0.01f);        // the joint's height plus the bar's half width
}

TEST(EmbreeScene, ZeroScaleInstanceLeavesTheBvhAndComesBack) {
  // Scale 0 hides an object (legal glTF). Embree cannot invert such an instance's matrix (its rays would
  // be NaN, which Debian's Embree asserts on): the instance leaves the BVH and returns with its scale.
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  ecs::Scheduler s;
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  gi::EmbreeScene bvh;
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  s.runFrame(w, {});
  Entity box{};
  w.each<Name>([&](Entity e, const Name& n) { if (n.value == "tall_box") box = e; });
  ASSERT_FALSE(box.isNull());
  const glm::vec3 centre = glm::vec3(w.get<WorldTransform>(box).matrix[3]) + glm::vec3(0, 0.3f, 0);
  const glm::vec3 from = centre + glm::vec3(0, 0, 0.9f), dir(0, 0, -1);
  gi::RayHit before = bvh.intersect(from, dir, 0.0f, 10.0f);
  ASSERT_TRUE(before.hit && before.entity == box);
  const size_t instances = bvh.stats().instances;

  w.write<Transform>(box).scale = glm::vec3(0.0f);
  s.runFrame(w, {});
  EXPECT_EQ(bvh.stats().instances, instances - 1);
  gi::RayHit hidden = bvh.intersect(from, dir, 0.0f, 10.0f);
  EXPECT_TRUE(hidden.hit) << "the back wall behind it";
  EXPECT_NE(hidden.entity, box);
  for (int i = 0; i < 64; ++i) {  // rays through where it was, in all directions: none may assert
    glm::vec3 d = glm::normalize(glm::vec3(std::sin(float(i)), std::cos(float(i) * 1.7f), std::sin(float(i) * 0.3f) - 0.5f));
    (void)bvh.intersect(centre + glm::vec3(0, 0, 0.5f), d, 0.0f, 10.0f);
  }
  // A NaN ray from a caller is a miss, not an assertion inside Embree.
  const float nan = std::nanf("");
  EXPECT_FALSE(bvh.intersect(glm::vec3(nan), dir, 0.0f, 10.0f).hit);
  EXPECT_FALSE(bvh.occluded(gi::Segment{glm::vec3(0, nan, 0), glm::vec3(0, 1, 0)}, 1e-4f));

  w.write<Transform>(box).scale = glm::vec3(1.0f);
  s.runFrame(w, {});
  EXPECT_EQ(bvh.stats().instances, instances);
  gi::RayHit back = bvh.intersect(from, dir, 0.0f, 10.0f);
  EXPECT_TRUE(back.hit && back.entity == box);
  EXPECT_NEAR(back.t, before.t, 1e-5f);
}

TEST(EmbreeScene, MeshesWithNanOrRunawayVerticesStayOutOfTheFrameAndTheBvh) {
  // A host may hand over NaN vertices, or a skin may pull a mesh to infinity at run time. Such a mesh
  // is left out of the snapshot (so of the bounds, voxels and shadows) and of the BVH, with no Embree
  // assertion, and comes back once its vertices are usable again.
  ecs::World w;
  AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  MeshData bad = makeBox({0.1f, 0.1f, 0.1f});
  bad.positions[3].y = std::nanf("");
  const MeshId badMesh = assets.addMesh(bad);
  EXPECT_FALSE(assets.mesh(badMesh).usable);
  const MeshId deforming = assets.addMesh(makeBox({0.1f, 0.1f, 0.1f}));
  auto addEntity = [&](MeshId mesh, glm::vec3 at) {
    Entity e = w.create();
    w.add(e, Transform{.translation = at});
    w.add(e, MeshInstance{mesh, true});
    w.add(e, Material{});
    return e;
  };
  Entity nanEntity = addEntity(badMesh, {0.5f, 1.0f, 0.0f});
  Entity boxEntity = addEntity(deforming, {-0.5f, 1.0f, 0.0f});
  ecs::Scheduler s;
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  gi::EmbreeScene bvh;
  s.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  s.runFrame(w, {});
  dyngi::render::RenderSnapshot snap = dyngi::render::extractSnapshot(w, assets, 0);
  EXPECT_EQ(snap.skippedDraws, 1u);
  for (const auto& d : snap.draws) EXPECT_NE(d.entity, nanEntity);
  EXPECT_TRUE(withinCoordinateRange(snap.sceneBounds.min) && withinCoordinateRange(snap.sceneBounds.max));
  const size_t instances = bvh.stats().instances;
  EXPECT_EQ(instances, snap.draws.size()) << "the NaN mesh is not in the BVH";
  auto hitsBox = [&] {
    gi::RayHit h = bvh.intersect({-0.5f, 1.0f, 0.9f}, {0, 0, -1}, 0.0f, 10.0f);
    return h.hit && h.entity == boxEntity;
  };
  ASSERT_TRUE(hitsBox());

  // The other box deforms into a runaway vertex (as a skin pulled by an infinite joint would): out...
  {
    MeshData& m = assets.meshForWrite(deforming);
    m.positions[0].x = 1e30f;
    m.computeBounds();
  }
  s.runFrame(w, {});
  EXPECT_EQ(bvh.stats().instances, instances - 1);
  EXPECT_FALSE(hitsBox());
  EXPECT_EQ(dyngi::render::extractSnapshot(w, assets, 1).skippedDraws, 2u);
  // ... and back when its vertices are sound again, though the entity itself never changed.
  {
    MeshData& m = assets.meshForWrite(deforming);
    m = makeBox({0.1f, 0.1f, 0.1f});
    m.version = 99;
    m.computeBounds();
  }
  s.runFrame(w, {});
  EXPECT_EQ(bvh.stats().instances, instances);
  EXPECT_TRUE(hitsBox());
}
