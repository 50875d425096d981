// Incremental VPL paths: invalidation against a brute-force oracle, the replacement budget and the
// fairness of the round-robin cursor.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "support/report.h"
#include "dyngi/engine/scene/transform_system.h"
#include "techniques/temporal/vpl_paths.h"
#include "scenes/builtin_scenes.h"
#include "support/scene_triangles.h"
#include "gi/skinned_bar_room.h"
#include "dyngi/gi/change_set.h"
#include "support/fence_scene.h"
#include "dyngi/engine/scene/animation.h"

using namespace dyngi;
using namespace dyngi::scene;

namespace {
// Propagates transforms, syncs the BVH, returns the snapshot and the entities that moved.
render::RenderSnapshot stepFrame(ecs::World& world, const AssetStore& assets, ecs::Scheduler& scheduler, gi::EmbreeScene& bvh,
                                 ecs::EntitySet* moved) {
  // Everything written since the previous frame happened at the current tick or later.
  const ecs::Tick since = world.tick() - 1;
  scheduler.runFrame(world, {});
  if (moved) {
    moved->clear();
    world.forEachChanged<WorldTransform>(since, [&](ecs::Entity e) { moved->insert(e); });
  }
  bvh.sync(world, assets, since);
  return render::extractSnapshot(world, assets, 0);
}

struct Fixture {
  ecs::World world;
  AssetStore assets;
  gi::EmbreeScene bvh;
  ecs::Scheduler scheduler;
  Fixture() {
    sample::buildBuiltinScene("cornell", world, assets);
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  }
  render::RenderSnapshot frame(ecs::EntitySet* moved = nullptr) { return stepFrame(world, assets, scheduler, bvh, moved); }
};

// 256 one-bounce VPLs in four temporal sets, filled at once, every set marked rendered: the starting
// point of the staleness tests.
constexpr uint32_t kStaleSets = 4;
gi::VplPaths freshPaths(Fixture& f, const render::RenderSnapshot& snap) {
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 256, .bounces = 1}, .temporalSets = kStaleSets});
  paths.update(snap, f.bvh, f.assets, {});
  EXPECT_EQ(paths.stats().valid, 256u);
  for (uint32_t s = 0; s < kStaleSets; ++s) paths.markSetRendered(s);
  return paths;
}
}  // namespace

// With the bounce tail on, the last bounce's probes (gathered by the temporal technique where they land)
// count too: a probe the occluder now blocks, or an escaped one it stands in, invalidates its VPL.
class VplPathsOccluder : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(BounceTail, VplPathsOccluder, ::testing::Bool());

TEST_P(VplPathsOccluder, InvalidatesExactlyWhatItBlocksAndDescendants) {
  const bool tail = GetParam();
  Fixture f;
  // An occluder parked far outside the room, where no light reaches.
  Entity occ = f.world.create();
  Transform ot;
  ot.translation = {0, 50, 0};
  f.world.add(occ, ot);
  f.world.add(occ, MeshInstance{f.assets.addMesh(makeBox({0.12f, 0.02f, 0.12f})), true});
  f.world.add(occ, Material{});
  ecs::EntitySet moved;
  auto snap = f.frame(&moved);
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 3000, .bounces = 3, .bounceTail = tail}, .reshootBudget = 100000});
  paths.update(snap, f.bvh, f.assets, moved);
  ASSERT_EQ(paths.stats().valid, 3000u);
  std::vector<gi::PathVpl> before = paths.vpls();

  // Move it just under the spot light.
  f.world.write<Transform>(occ).translation = {0.3f, 1.2f, 0.1f};
  snap = f.frame(&moved);
  ASSERT_TRUE(moved.count(occ));
  paths.invalidate(snap, f.bvh, moved);

  // Oracle: brute-force segment tests against the occluder's triangles only.
  std::vector<test::WorldTriangle> occTris;
  for (auto& t : test::worldTriangles(f.world, f.assets))
    if (t.entity == occ) occTris.push_back(t);
  const float eps = 1e-4f * glm::length(snap.sceneBounds.extent());
  std::vector<bool> expectInvalid(before.size(), false);
  int blocked = 0, blockedAfterBounce = 0, escapedNowBlocked = 0, probesBlocked = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    const gi::PathVpl& v = before[i];
    uint32_t b = i % 3;
    if (b > 0 && expectInvalid[i - 1]) {  // descendant of an invalidated VPL
      expectInvalid[i] = true;
      continue;
    }
    if (!v.placed) {
      // An escaped ray of its own (not a later bounce of an escaped path): invalid if the occluder now
      // stands in it.
      if (b > 0 && !before[i - 1].placed) continue;
      const float t = test::bruteForceHit(occTris, v.rayOrigin, v.rayDir, 0.0f, 1e30f);
      if (t > 0) expectInvalid[i] = true, ++escapedNowBlocked;
      continue;
    }
    // Its own ray, from where it was shot up to just before it.
    const float t = test::bruteForceHit(occTris, v.rayOrigin, v.rayDir, 0.0f, glm::dot(v.position - v.rayOrigin, v.rayDir) - eps);
    if (t > 0) expectInvalid[i] = true, ++blocked, blockedAfterBounce += b > 0;
    if (tail && b == 2 && !expectInvalid[i]) {
      // Its probe, as shot, up to just before where it landed (or on, if it left the scene).
      ASSERT_TRUE(v.probeSurface != occ);
      const glm::vec3& o = v.probeOrigin;
      const float end = v.probeSurface.isNull() ? 1e30f : glm::dot(v.probePosition - o, v.probeDir) - eps;
      if (test::bruteForceHit(occTris, o, v.probeDir, 0.0f, end) > 0) expectInvalid[i] = true, ++probesBlocked;
    }
  }
  if (tail) {
    ASSERT_GT(probesBlocked, 3) << "the occluder must block some probes";
  }
  ASSERT_GT(blocked, 30) << "the occluder must block a fair share of paths";
  ASSERT_GT(blockedAfterBounce, 3) << "and some segments between VPLs";
  int mismatches = 0, invalid = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    bool isInvalid = !paths.vpls()[i].valid;
    invalid += isInvalid;
    mismatches += isInvalid != expectInvalid[i];
  }
  dyngi::test::report("occluder: %d VPLs blocked directly (%d from a parent VPL), %d escaped rays it now stands in, %d probes blocked, %d invalid "
              "with descendants, %d mismatches\n",
              blocked, blockedAfterBounce, escapedNowBlocked, probesBlocked, invalid, mismatches);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(paths.stats().invalidatedThisFrame, uint32_t(invalid));
}

// Nothing changed, nothing invalid: a large pool, from a spot, a point light and the sun, passes its
// own check. (A check that disagreed with the shot on a grazing ray would redraw that VPL, traced again
// with its own stream to the same place, every frame.)
TEST(VplPaths, AnUnchangedSceneInvalidatesNothing) {
  for (LightType type : {LightType::Spot, LightType::Point, LightType::Directional}) {
    Fixture f;
    f.world.each<Light>([&](Entity e, const Light&) { f.world.write<Light>(e).type = type; });
    auto snap = f.frame();
    gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 30000, .bounces = 3, .bounceTail = true}, .reshootBudget = 100000});
    paths.update(snap, f.bvh, f.assets, {});
    ASSERT_EQ(paths.stats().valid, 30000u);
    ecs::EntitySet none;
    paths.invalidate(snap, f.bvh, none);
    EXPECT_EQ(paths.stats().invalidatedThisFrame, 0u) << "light type " << int(type);
    // The light listed as moved (it did not): the tail's probes are traced again, and each must still
    // land where it did.
    ecs::EntitySet light{snap.lights.at(0).entity};
    paths.invalidate(snap, f.bvh, light);
    EXPECT_EQ(paths.stats().invalidatedThisFrame, 0u) << "light type " << int(type) << ", probes checked";
  }
}

// A probe's surface listed as moved invalidates the last-bounce VPL it belongs to (the temporal technique
// gathers the probe where it landed), besides the VPLs on that surface and their descendants. The entity
// did not really move, so no ray changed and nothing else may go.
TEST(VplPaths, AProbesSurfaceMovingInvalidatesItsVpl) {
  Fixture f;
  auto snap = f.frame();
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 3000, .bounces = 3, .bounceTail = true}, .reshootBudget = 100000});
  paths.update(snap, f.bvh, f.assets, {});
  ASSERT_EQ(paths.stats().valid, 3000u);
  const std::vector<gi::PathVpl> before = paths.vpls();
  ecs::Entity box{};  // a surface some probes land on that is not the room
  for (uint32_t i = 2; i < before.size() && box.isNull(); i += 3)
    if (!before[i].probeSurface.isNull() && before[i].probeSurface != before[0].surface) box = before[i].probeSurface;
  ASSERT_FALSE(box.isNull());
  std::vector<bool> expectInvalid(before.size(), false);
  int probes = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    const uint32_t b = i % 3;
    if (b > 0 && expectInvalid[i - 1]) expectInvalid[i] = true;
    if (before[i].placed && before[i].surface == box) expectInvalid[i] = true;
    if (b == 2 && !expectInvalid[i] && before[i].probeSurface == box) expectInvalid[i] = true, ++probes;
  }
  ASSERT_GT(probes, 10);
  ecs::EntitySet moved{box};
  paths.invalidate(snap, f.bvh, moved);
  int mismatches = 0;
  for (uint32_t i = 0; i < before.size(); ++i) mismatches += paths.vpls()[i].valid == expectInvalid[i];
  EXPECT_EQ(mismatches, 0) << probes << " probes on the entity";
  // Reshot with their own streams in an unchanged scene, they come back where they were, probes too.
  paths.replace(snap, f.bvh, f.assets);
  for (uint32_t i = 2; i < before.size(); i += 3)
    if (expectInvalid[i] && before[i].probeSurface == box) {
      ASSERT_TRUE(paths.vpls()[i].valid);
      EXPECT_LT(glm::distance(paths.vpls()[i].probePosition, before[i].probePosition), 1e-5f) << i;
    }
}

// A sun over ground 400 m wide: with a reach of 64 m it shoots every VPL over the sphere of that radius
// around a focus near the camera, and their flux over a 20 m disc around the camera's feet is what the
// sun leaves there (albedo x E x cos, the disc's area), as without a focus but with 20 times the VPLs
// there. The focus holds while the camera moves within its cell; a step beyond reshoots the sun's paths
// around the new one.
TEST(VplPaths, ASunOverAWideWorldShootsItsVplsAroundTheCamera) {
  constexpr float kE = 2.0f, kAlbedo = 0.5f, kReach = 64.0f, kDisc = 20.0f;
  const glm::vec3 sunDir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  ecs::World world;
  AssetStore assets;
  gi::EmbreeScene bvh;
  ecs::Scheduler scheduler;
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  sample::addSceneMesh(world, assets, makeQuad({-200, 0, 200}, {400, 0, 0}, {0, 0, -400}), glm::vec3(kAlbedo), {}, false, "ground");
  Transform tower;  // far from the camera: it gives the scene its height, so the camera stands inside it
  tower.translation = {-150.0f, 10.0f, -150.0f};
  sample::addSceneMesh(world, assets, makeBox({5.0f, 10.0f, 5.0f}), glm::vec3(kAlbedo), tower, false, "tower");
  Entity sun = world.create();
  Transform st;
  st.rotation = glm::quatLookAtRH(sunDir, glm::vec3(0, 1, 0));
  world.add(sun, st);
  world.add(sun, Light{.type = LightType::Directional, .intensity = kE});
  Entity cam = world.create();
  Transform ct;
  ct.translation = {100.0f, 2.0f, 50.0f};
  world.add(cam, ct);
  world.add(cam, Camera{});
  world.add(cam, ActiveCamera{});
  auto snap = stepFrame(world, assets, scheduler, bvh, nullptr);
  ASSERT_EQ(snap.lights.size(), 1u);

  struct Shot {
    double fluxNearCamera = 0;  // luminance over the disc around the camera's feet
    uint32_t nearCamera = 0, outsideFocus = 0;
  };
  auto measure = [&](const gi::VplPaths& paths, const glm::vec3& camera) {
    Shot s;
    const gi::CameraFocus& f = paths.focus();
    for (const gi::PathVpl& v : paths.vpls()) {
      if (!v.valid || !v.placed) continue;
      const glm::vec3 d = v.position - f.centre;
      s.outsideFocus += glm::length(d - glm::dot(d, sunDir) * sunDir) > f.radius * 1.0001f;  // off the disc's cylinder
      if (glm::length(glm::vec2(v.position.x - camera.x, v.position.z - camera.z)) < kDisc) {
        ++s.nearCamera;
        s.fluxNearCamera += double(v.flux.g);
      }
    }
    return s;
  };
  const double truth = kAlbedo * kE * -sunDir.y * 3.14159265 * kDisc * kDisc;
  gi::VplPaths wide(gi::TemporalOptions{.vpl = {.vpls = 4096, .bounces = 1, .directionalReach = 0.0f}, .reshootBudget = 100000});
  gi::VplPaths focused(gi::TemporalOptions{.vpl = {.vpls = 4096, .bounces = 1, .directionalReach = kReach}, .reshootBudget = 100000});
  wide.update(snap, bvh, assets, {});
  focused.update(snap, bvh, assets, {});
  ASSERT_TRUE(wide.focus().wholeScene);
  ASSERT_FALSE(focused.focus().wholeScene);
  EXPECT_LE(glm::distance(focused.focus().centre, ct.translation), 0.5f * std::sqrt(3.0f) * 0.5f * kReach + 1e-3f) << "the camera within the focus' cell";
  const Shot w = measure(wide, ct.translation), f = measure(focused, ct.translation);
  dyngi::test::report("sun over 400 m: %u VPLs within %.0f m of the camera over the whole scene (flux %.4f of the truth), %u with a %.0f m reach "
                      "(%.4f), %u outside its focus\n",
                      w.nearCamera, kDisc, w.fluxNearCamera / truth, f.nearCamera, kReach, f.fluxNearCamera / truth, f.outsideFocus);
  EXPECT_EQ(f.outsideFocus, 0u);
  EXPECT_GT(f.nearCamera, 15 * std::max(w.nearCamera, 1u));
  EXPECT_NEAR(f.fluxNearCamera / truth, 1.0, 0.03);

  // 10 m on, within the focus' cell of 32 m (the camera starts 4 m into it along x): nothing to reshoot.
  auto moveCamera = [&](float dx) {
    world.write<Transform>(cam).translation.x += dx;
    snap = stepFrame(world, assets, scheduler, bvh, nullptr);
    focused.invalidate(snap, bvh, {});
  };
  const glm::vec3 before = focused.focus().centre;
  moveCamera(10.0f);
  EXPECT_EQ(focused.focus().centre, before);
  EXPECT_EQ(focused.stats().invalidatedThisFrame, 0u);
  // 60 m on: the focus moves, every path of the sun is reshot around it.
  moveCamera(60.0f);
  EXPECT_NE(focused.focus().centre, before);
  EXPECT_EQ(focused.stats().invalidatedThisFrame, 4096u);
  focused.replace(snap, bvh, assets);
  const Shot moved = measure(focused, world.get<Transform>(cam).translation);
  EXPECT_EQ(focused.stats().valid, 4096u);
  EXPECT_EQ(moved.outsideFocus, 0u);
  EXPECT_NEAR(moved.fluxNearCamera / truth, 1.0, 0.03);
  // A camera above everything (outside the scene's bounds) sees the whole scene: no focus.
  world.write<Transform>(cam).translation.y = 500.0f;
  snap = stepFrame(world, assets, scheduler, bvh, nullptr);
  focused.invalidate(snap, bvh, {});
  EXPECT_TRUE(focused.focus().wholeScene);
}

TEST(VplPaths, BudgetIsRespectedRestoreIsTimelyAndCursorIsFair) {
  Fixture f;
  auto snap = f.frame();
  const uint32_t budget = 37;
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 600, .bounces = 2}, .reshootBudget = budget, .reshootBurst = 0});
  ecs::EntitySet none;
  // From empty: valid grows by exactly the budget per frame and is complete after ceil(600/37) frames.
  uint32_t frames = 0;
  while (paths.stats().valid < 600 && frames < 100) {
    paths.update(snap, f.bvh, f.assets, none);
    EXPECT_LE(paths.stats().replacedThisFrame, budget);
    ++frames;
  }
  EXPECT_EQ(frames, (600 + budget - 1) / budget);

  // Moving the light invalidates everything; each move is followed by a full restore in time.
  Entity light{};
  f.world.each<Light>([&](Entity e, const Light&) { light = e; });
  for (int round = 0; round < 6; ++round) {
    f.world.write<Transform>(light).translation.x = 0.1f * float(round + 1);
    snap = f.frame();
    paths.invalidate(snap, f.bvh, none);
    uint32_t invalid = 600 - paths.stats().valid;
    EXPECT_EQ(invalid, 600u);
    paths.replace(snap, f.bvh, f.assets);
    uint32_t n = 1;
    while (paths.stats().valid < 600 && n < 100) {
      paths.update(snap, f.bvh, f.assets, none);
      EXPECT_LE(paths.stats().replacedThisFrame, budget);
      ++n;
    }
    EXPECT_LE(n, (invalid + budget - 1) / budget) << "round " << round;
  }
  // Fairness: every VPL was reshot once per round (7 fills in all), none starved or favoured.
  auto [mn, mx] = std::minmax_element(paths.reshootCounts().begin(), paths.reshootCounts().end());
  EXPECT_EQ(*mn, 7u);
  EXPECT_EQ(*mx, 7u);
}

// More invalid VPLs than the budget: all of them are reshot at once, up to the burst limit.
TEST(VplPaths, ABurstRefillsThePoolAtOnceUpToItsLimit) {
  Fixture f;
  auto snap = f.frame();
  ecs::EntitySet none;
  gi::VplPaths unlimited(gi::TemporalOptions{.vpl = {.vpls = 600, .bounces = 2}, .reshootBudget = 37, .reshootBurst = 4096});
  unlimited.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(unlimited.stats().valid, 600u) << "one frame";
  gi::VplPaths limited(gi::TemporalOptions{.vpl = {.vpls = 600, .bounces = 2}, .reshootBudget = 37, .reshootBurst = 100});
  uint32_t frames = 0;
  while (limited.stats().valid < 600 && frames < 100) {
    limited.update(snap, f.bvh, f.assets, none);
    EXPECT_LE(limited.stats().replacedThisFrame, 100u);
    ++frames;
  }
  EXPECT_EQ(frames, 6u);
}

// A set's stored light is stale (TemporalIndirect drops it) after its VPLs' light was switched or jumped,
// not after the light crept past its tolerance or an occluder moved.
TEST(VplPaths, OnlyASwitchedOrJumpingLightMakesSetsStale) {
  Fixture f;
  auto snap = f.frame();
  ecs::EntitySet none;
  const uint32_t T = kStaleSets;
  gi::VplPaths paths = freshPaths(f, snap);
  auto renderAll = [&] {
    for (uint32_t s = 0; s < T; ++s) paths.markSetRendered(s);
  };
  auto maxStale = [&] {
    float m = 0;
    for (uint32_t s = 0; s < T; ++s) m = std::max(m, paths.setStaleFraction(s));
    return m;
  };
  EXPECT_EQ(maxStale(), 0.0f);
  Entity light{};
  f.world.each<Light>([&](Entity e, const Light&) { light = e; });
  const float diagonal = glm::length(snap.sceneBounds.extent());
  const float tolerance = gi::TemporalOptions{}.lightMoveTolerance * diagonal;
  // Crept 1.5 tolerances: every VPL reshot (the burst), none stale.
  f.world.write<Transform>(light).translation.x += 1.5f * tolerance;
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().replacedThisFrame, 256u);
  for (uint32_t s = 0; s < T; ++s) EXPECT_TRUE(paths.setDirty(s));
  EXPECT_EQ(maxStale(), 0.0f);
  renderAll();
  // Jumped (kLightJump tolerances and more): every set stale.
  f.world.write<Transform>(light).translation.x -= 1.2f * gi::VplPaths::kLightJump * tolerance;
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  for (uint32_t s = 0; s < T; ++s) EXPECT_EQ(paths.setStaleFraction(s), 1.0f) << s;
  renderAll();
  // Switched off: stale (the sets held its light); rendered dark, then switched on: stale again.
  f.world.write<Light>(light).enabled = false;
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().valid, 0u);
  EXPECT_EQ(maxStale(), 1.0f);
  renderAll();
  f.world.write<Light>(light).enabled = true;
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().valid, 256u);
  for (uint32_t s = 0; s < T; ++s) EXPECT_EQ(paths.setStaleFraction(s), 1.0f) << s;
}

// A second light switched on changes every light's share of the paths: every path is redrawn (before,
// the first light kept all of them, with fluxes divided by a share of 1, and the second got none).
TEST(VplPaths, ASecondLightSwitchedOnRedrawsEveryPath) {
  Fixture f;
  Entity second = f.world.create();
  Transform t;
  t.translation = {0.5f, 1.5f, 0.5f};
  f.world.add(second, t);
  f.world.add(second, Light{.type = LightType::Point, .intensity = 2.0f, .enabled = false});
  auto snap = f.frame();
  ecs::EntitySet none;
  const uint32_t T = kStaleSets;
  gi::VplPaths paths = freshPaths(f, snap);
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().invalidatedThisFrame, 0u) << "nothing changed";
  f.world.write<Light>(second).enabled = true;
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().invalidatedThisFrame, 256u);
  EXPECT_EQ(paths.stats().valid, 256u) << "and reshot at once (the burst)";
  for (uint32_t s = 0; s < T; ++s) EXPECT_EQ(paths.setStaleFraction(s), 1.0f) << s;
  // Some VPLs now come from the point light: they lie outside the spot's cone (the spot points down
  // from the ceiling's centre with a 45-degree cone), e.g. on the ceiling.
  uint32_t onCeiling = 0;
  for (const gi::PathVpl& v : paths.vpls()) onCeiling += v.placed && v.position.y > 1.99f;
  EXPECT_GT(onCeiling, 0u);
}

TEST(VplPaths, TemporalSetsPartitionThePool) {
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 512, .bounces = 1}, .temporalSets = 16});
  std::vector<int> seen(512, 0);
  for (uint32_t set = 0; set < 16; ++set)
    for (uint32_t i = set; i < 512; i += 16) {
      EXPECT_EQ(paths.setOf(i), set);
      ++seen[i];
    }
  for (int s : seen) EXPECT_EQ(s, 1);
}

TEST(VplPaths, LightSwitchedOffLeavesNoValidVpl) {
  Fixture f;
  auto snap = f.frame();
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 256, .bounces = 2}, .reshootBudget = 1000});
  ecs::EntitySet none;
  paths.update(snap, f.bvh, f.assets, none);
  ASSERT_EQ(paths.stats().valid, 256u);
  f.world.each<Light>([&](Entity e, const Light&) { f.world.commands().run([e](ecs::World& w) { w.write<Light>(e).enabled = false; }); });
  f.world.flushCommands();
  snap = f.frame();
  paths.update(snap, f.bvh, f.assets, none);
  EXPECT_EQ(paths.stats().valid, 0u) << "no light: nothing to reshoot from";
}

TEST(VplPaths, DeformingSkinnedMeshInvalidatesExactlyWhatItBlocksAndWhatLiesOnIt) {
  // The two-bone bar stands in the spot's cone and folds over as its animation plays. The VPLs to
  // invalidate are those on the bar, those whose segment the folded bar now blocks, and their
  // descendants: a brute-force oracle over the deformed triangles decides, VPL by VPL.
  test::SkinnedBarRoom room({0.25f, 0.0f, 0.1f});
  ASSERT_EQ(room.bar.error, "");
  ecs::World& world = room.world;
  AssetStore& assets = room.assets;
  const test::SkinnedBar& bar = room.bar;
  ecs::Scheduler& scheduler = room.scheduler;
  gi::EmbreeScene bvh;
  const MeshId deformed = room.deformed;
  uint32_t version = 0;
  // One frame at time t; `moved` as the GI system finds it: entities whose deformed mesh changed.
  auto frame = [&](double t, uint64_t n, ecs::EntitySet& moved) {
    ecs::Tick since = world.tick();
    scheduler.runFrame(world, ecs::FrameTime{1.0 / 60, t, n});
    bvh.sync(world, assets, n == 0 ? 0 : since);
    moved.clear();
    if (assets.mesh(deformed).version != version) moved.insert(bar.mesh);
    version = assets.mesh(deformed).version;
    return render::extractSnapshot(world, assets, n);
  };
  ecs::EntitySet moved;
  // Hold the animation at t = 0 while the paths are shot: the bar stands straight.
  world.write<Animator>(bar.animator).playing = false;
  auto snap = frame(0.0, 0, moved);
  // The paths' own segments: the tail's probes, invalidated by what they cross too, have their test above.
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 3000, .bounces = 3, .bounceTail = false}, .reshootBudget = 100000});
  paths.update(snap, bvh, assets, moved);
  ASSERT_EQ(paths.stats().valid, 3000u);
  const std::vector<gi::PathVpl> before = paths.vpls();
  int onBar = 0;
  for (const auto& v : before) onBar += v.placed && v.surface == bar.mesh;
  ASSERT_GT(onBar, 10) << "the spot lights the bar";

  // Half a second on: the upper half has turned 45 degrees.
  {
    Animator& a = world.write<Animator>(bar.animator);
    a.playing = true;
    a.time = 0.5f;
  }
  snap = frame(0.5, 1, moved);
  ASSERT_TRUE(moved.count(bar.mesh)) << "the deformation is seen as a change";
  paths.invalidate(snap, bvh, moved);

  // The implementation re-tests every valid VPL's segment against the whole scene, so the oracle does
  // too (a path shot last frame is tested for the first time now, and a corner can block it); the bar's
  // own share is counted apart.
  const std::vector<test::WorldTriangle> allTris = test::worldTriangles(world, assets);
  std::vector<test::WorldTriangle> barTris;
  for (auto& t : allTris)
    if (t.entity == bar.mesh) barTris.push_back(t);
  const float eps = 1e-4f * glm::length(snap.sceneBounds.extent());
  std::vector<bool> expectInvalid(before.size(), false);
  int blocked = 0, surface = 0, escapedNowBlocked = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    const gi::PathVpl& v = before[i];
    const uint32_t b = i % 3;
    if (b > 0 && expectInvalid[i - 1]) {
      expectInvalid[i] = true;
      continue;
    }
    if (!v.placed) {
      // An escaped ray of its own: invalid if the folded bar now stands in it.
      if (b > 0 && !before[i - 1].placed) continue;
      if (test::bruteForceHit(allTris, v.rayOrigin, v.rayDir, 0.0f, 1e30f) > 0)
        expectInvalid[i] = true, ++escapedNowBlocked;
      continue;
    }
    if (v.surface == bar.mesh) {
      expectInvalid[i] = true, ++surface;
      continue;
    }
    const float reach = glm::dot(v.position - v.rayOrigin, v.rayDir) - eps;  // its own ray, up to just before it
    if (test::bruteForceHit(barTris, v.rayOrigin, v.rayDir, 0.0f, reach) > 0) expectInvalid[i] = true, ++blocked;
    else if (test::bruteForceHit(allTris, v.rayOrigin, v.rayDir, 0.0f, reach) > 0) expectInvalid[i] = true;
  }
  ASSERT_GT(blocked, 20) << "the folded bar must block a fair share of paths";
  int mismatches = 0, invalid = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    bool isInvalid = !paths.vpls()[i].valid;
    invalid += isInvalid;
    mismatches += isInvalid != expectInvalid[i];
  }
  dyngi::test::report("skinned bar: %d VPLs on it, %d newly blocked, %d escaped rays it now stands in, %d invalid with descendants, %d mismatches\n",
              surface, blocked, escapedNowBlocked, invalid, mismatches);
  EXPECT_EQ(mismatches, 0);
}

// The bounce tail's ratio (shaders/shared/bounce_tail.h) in two analytic cases. Inside a closed box every
// probe lands on a wall, so a further bounce keeps exactly the walls' albedo per channel and the last
// bounce's scale is 1 / (1 - albedo). Over a lone floor every probe leaves the scene: the scale is 1.
TEST(VplPaths, BounceTailRatioIsTheAlbedoInAClosedBoxAndZeroOverALoneFloor) {
  auto scaleOf = [](bool closed) {
    ecs::World world;
    AssetStore assets;
    ecs::Scheduler scheduler;
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
    const glm::vec3 albedo{0.5f, 0.25f, 0.75f};
    Entity room = world.create();
    world.add(room, Transform{});
    world.add(room, MeshInstance{assets.addMesh(closed ? makeBox({1, 1, 1}) : makeQuad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2})), true});
    world.add(room, Material{.baseColor = glm::vec4(albedo, 1.0f)});
    Entity light = world.create();
    Transform lt;
    lt.translation = {0.2f, 0.5f, -0.1f};
    world.add(light, lt);
    world.add(light, Light{.type = LightType::Point, .intensity = 3.0f});
    scheduler.runFrame(world, {});
    gi::EmbreeScene bvh;
    bvh.sync(world, assets, 0);
    const auto snap = render::extractSnapshot(world, assets, 0);
    gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 600, .bounces = 2, .bounceTail = true}, .reshootBudget = 100000});
    paths.update(snap, bvh, assets, {});
    EXPECT_EQ(paths.stats().valid, 600u);
    return paths.bounceTailScale();
  };
  const glm::vec3 closed = scaleOf(true), open = scaleOf(false);
  EXPECT_NEAR(closed.r, 1.0f / (1.0f - 0.5f), 1e-3f);
  EXPECT_NEAR(closed.g, 1.0f / (1.0f - 0.25f), 1e-3f);
  EXPECT_NEAR(closed.b, 1.0f / (1.0f - 0.75f), 1e-3f);
  EXPECT_EQ(open, glm::vec3(1.0f));
  // Off, nothing is scaled.
  EXPECT_EQ(gi::VplPaths(gi::TemporalOptions{.vpl = {.bounceTail = false}}).bounceTailScale(), glm::vec3(1.0f));
}

namespace {
float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// A closed 2 m box (albedo 0.5) with a 0.4 m emissive panel under its top, facing down; optionally a
// spot light too, shining down onto the floor (never onto the panel).
struct EmitterRoom {
  ecs::World world;
  AssetStore assets;
  ecs::Scheduler scheduler;
  gi::EmbreeScene bvh;
  Entity panel, light;
  static constexpr glm::vec3 kRadiance{4.0f, 2.0f, 1.0f};
  static constexpr float kSide = 0.4f;
  explicit EmitterRoom(bool withLight) {
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
    Entity room = world.create();
    world.add(room, Transform{});
    world.add(room, MeshInstance{assets.addMesh(makeBox({1, 1, 1})), true});
    world.add(room, Material{.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)});
    panel = world.create();
    world.add(panel, Transform{});
    world.add(panel, MeshInstance{assets.addMesh(makeQuad({-kSide / 2, 0.8f, -kSide / 2}, {kSide, 0, 0}, {0, 0, kSide})), true});
    world.add(panel, Material{.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), .emissive = kRadiance});
    if (withLight) {
      light = world.create();
      Transform lt;
      lt.translation = {0.3f, -0.5f, 0.2f};
      lt.rotation = glm::rotation(glm::vec3(0, 0, -1), glm::vec3(0, -1, 0));  // lights shine along local -Z
      world.add(light, lt);
      world.add(light, Light{.type = LightType::Spot, .intensity = 2.0f});
    }
  }
  render::RenderSnapshot frame(ecs::EntitySet* moved = nullptr) { return stepFrame(world, assets, scheduler, bvh, moved); }
};
}  // namespace

// Paths from an emissive panel (vpl/emitters.h): their first VPLs lie on the panel, face the way it emits,
// and carry exactly its flux (uniform radiance: 2 pi A L over both sides, every sample the same share).
TEST(VplPaths, EmissivePanelStartsPathsOnItselfWithItsExactFlux) {
  EmitterRoom room(false);
  auto snap = room.frame();
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 2000, .bounces = 2}, .reshootBudget = 100000});
  paths.update(snap, room.bvh, room.assets, {});
  ASSERT_EQ(paths.stats().valid, 2000u);
  glm::dvec3 flux(0.0);
  uint32_t down = 0, onPanel = 0, bounced = 0;
  for (uint32_t i = 0; i < 2000; i += 2) {
    const gi::PathVpl& v = paths.vpls()[i];
    ASSERT_TRUE(v.placed);
    flux += glm::dvec3(v.flux);
    onPanel += std::abs(v.position.y - 0.8f) < 1e-4f && std::abs(v.position.x) <= 0.2001f && std::abs(v.position.z) <= 0.2001f;
    down += v.normal.y < -0.99f;
    bounced += paths.vpls()[i + 1].placed && luminance(paths.vpls()[i + 1].flux) > 0.0f;
  }
  const glm::dvec3 expected = glm::dvec3(EmitterRoom::kRadiance) * (2.0 * 3.14159265358979 * EmitterRoom::kSide * EmitterRoom::kSide);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c] / expected[c], 1.0, 1e-4) << c;
  EXPECT_EQ(onPanel, 1000u);
  EXPECT_NEAR(down / 1000.0, 0.5, 0.06) << "both sides emit";
  EXPECT_EQ(bounced, 1000u) << "a closed room: every path's second VPL lands";
}

// An emitter competes with the lights by power, and its paths follow it: moved, it invalidates them (and
// only them); its emission changed or switched off, they are redrawn (hard), and off, none starts from it.
TEST(VplPaths, EmitterPathsShareByPowerAndFollowTheEmitter) {
  EmitterRoom room(true);
  ecs::EntitySet moved;
  auto snap = room.frame(&moved);
  // Without the tail: a probe that landed on the moved panel would invalidate its path too.
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 4000, .bounces = 1, .bounceTail = false}, .reshootBudget = 100000});
  paths.update(snap, room.bvh, room.assets, moved);
  auto fromPanel = [&] {
    uint32_t n = 0;
    for (const gi::PathVpl& v : paths.vpls()) n += v.valid && v.placed && v.surface == room.panel;
    return n;
  };
  // Power: the panel 2 pi A L (luminance), the spot 2 pi I (1 - cos outer).
  const float panelPower = 2.0f * 3.14159265f * EmitterRoom::kSide * EmitterRoom::kSide * luminance(EmitterRoom::kRadiance);
  const float lightPower = 2.0f * 2.0f * 3.14159265f * (1.0f - std::cos(Light{}.outerConeAngle));
  const double share = panelPower / (panelPower + lightPower), n = 4000;
  EXPECT_NEAR(fromPanel() / n, share, 4.0 * std::sqrt(share * (1 - share) / n)) << "paths drawn by power";

  // Moved: exactly its paths are invalid.
  const uint32_t before = fromPanel();
  room.world.write<Transform>(room.panel).translation = {0.1f, -0.05f, 0.0f};
  snap = room.frame(&moved);
  ASSERT_TRUE(moved.count(room.panel));
  paths.invalidate(snap, room.bvh, moved);
  EXPECT_EQ(paths.stats().invalidatedThisFrame, before);
  paths.replace(snap, room.bvh, room.assets);
  EXPECT_EQ(paths.stats().valid, 4000u);

  // Emission changed: its paths are redrawn, hard (their sets' stored light says little now).
  for (uint32_t s = 0; s < paths.settings().temporalSets; ++s) paths.markSetRendered(s);
  room.world.write<Material>(room.panel).emissive = EmitterRoom::kRadiance * 2.0f;
  snap = room.frame(&moved);
  paths.update(snap, room.bvh, room.assets, moved);
  EXPECT_GT(paths.setStaleFraction(0), 0.3f);
  EXPECT_NEAR(fromPanel() / n, 2 * panelPower / (2 * panelPower + lightPower), 0.05);

  // Switched off: nothing starts from it any more.
  room.world.write<Material>(room.panel).emissive = glm::vec3(0.0f);
  snap = room.frame(&moved);
  paths.update(snap, room.bvh, room.assets, moved);
  EXPECT_EQ(fromPanel(), 0u);
  EXPECT_EQ(paths.stats().valid, 4000u);
}

// Textured emission: a panel whose emissive texture is black on one half (x < 0) and white on the other
// starts its paths' light from the white half only, with the flux of that half (2 pi (A / 2) L): each
// sample carries the texel it lands on.
TEST(VplPaths, TexturedEmitterStartsItsLightWhereItsTextureEmits) {
  EmitterRoom room(false);
  TextureData t;
  t.width = t.height = 8;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x) {
      const uint8_t v = x < 4 ? 0 : 255;
      t.rgba8.insert(t.rgba8.end(), {v, v, v, 255});
    }
  room.world.write<Material>(room.panel).emissiveTexture = room.assets.addTexture(t);
  auto snap = room.frame();
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 4000, .bounces = 1}, .reshootBudget = 100000});
  paths.update(snap, room.bvh, room.assets, {});
  glm::dvec3 flux(0.0);
  for (const gi::PathVpl& v : paths.vpls()) {
    if (!v.placed) continue;
    // The panel's quad: u runs along +x; the bilinear lookup (wrapping) blends the halves within half a
    // texel (2.5 cm) of the seam and of the panel's edges.
    if (v.position.x < -0.03f && v.position.x > -0.17f) {
      EXPECT_EQ(luminance(v.flux), 0.0f) << "light from the black half at x " << v.position.x;
    }
    flux += glm::dvec3(v.flux);
  }
  const glm::dvec3 expected = glm::dvec3(EmitterRoom::kRadiance) * (2.0 * 3.14159265358979 * EmitterRoom::kSide * EmitterRoom::kSide / 2.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c] / expected[c], 1.0, 0.08) << c;
}

// An alpha cut switched on and off again: the change set counts it as geometry (to a ray the surface
// vanished or appeared), so the paths that ended on the fence's now-cut half are redrawn and the sun
// reaches the floor through it; switched off, the paths through the hole are blocked again.
TEST(VplPaths, AnAlphaCutToggledRedrawsThePathsItChanges) {
  ecs::World w;
  AssetStore assets;
  const test::FenceScene fence = test::floorUnderAFence(w, assets);
  w.write<Material>(fence.fence).alphaMask = false;  // solid to start with
  TransformSystem().run(w, {});
  gi::ChangeTracker tracker;
  tracker.compute(w, assets, 0);
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  gi::VplPaths paths(gi::TemporalOptions{.vpl = {.vpls = 4000, .bounces = 2}, .reshootBudget = 100000});
  paths.update(render::extractSnapshot(w, assets, 0), bvh, assets, {});
  auto onCutHalf = [](const glm::vec3& p) { return std::abs(p.y - test::kFenceHeight) < 1e-3f && p.x < 0.0f; };
  auto underHole = [](const glm::vec3& p) { return std::abs(p.y) < 1e-3f && test::underTheFence(p) == test::Under::Hole; };
  struct Counts {
    int onCut = 0, underHole = 0;
  };
  auto count = [&](bool firstBounceOnly) {
    Counts c;
    for (uint32_t i = 0; i < paths.vpls().size(); ++i) {
      const gi::PathVpl& v = paths.vpls()[i];
      if (!v.valid || !v.placed || (firstBounceOnly && i % 2 != 0)) continue;
      c.onCut += onCutHalf(v.position);
      c.underHole += underHole(v.position);
    }
    return c;
  };
  const Counts solid = count(true);
  const std::vector<gi::PathVpl> before = paths.vpls();
  ASSERT_GT(solid.onCut, 50) << "the sun lights the whole fence";
  ASSERT_EQ(solid.underHole, 0) << "and nothing under it";

  // The cut on: a material write, no transform.
  auto toggle = [&](bool masked) {
    const ecs::Tick since = w.tick();
    w.advanceTick();
    w.write<Material>(fence.fence).alphaMask = masked;
    const gi::ChangeSet changes = tracker.compute(w, assets, since);
    bvh.sync(w, assets, since);
    EXPECT_TRUE(changes.moved.empty());
    EXPECT_EQ(changes.cutChanged, std::vector<ecs::Entity>{fence.fence});
    paths.invalidate(render::extractSnapshot(w, assets, 0), bvh, changes.geometryChanged());
  };
  toggle(true);
  EXPECT_EQ(count(false).onCut, 0) << "no VPL left on the cut half";
  paths.replace(render::extractSnapshot(w, assets, 0), bvh, assets);
  const Counts cut = count(true);
  EXPECT_EQ(cut.onCut, 0);
  EXPECT_GT(cut.underHole, 30) << "the sun's paths pass the cut";
  // The pool a fresh shot with the same seed draws in the cut scene, VPL for VPL: the redrawn paths keep
  // their random streams, so the region that changed gets its full share, not the share of the reshot
  // paths that happen to fall there.
  const auto differences = [](const std::vector<gi::PathVpl>& a, const std::vector<gi::PathVpl>& b) {
    int n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += a[i].placed != b[i].placed || glm::distance(a[i].position, b[i].position) > 1e-5f;
    return n;
  };
  gi::VplPaths fresh(gi::TemporalOptions{.vpl = {.vpls = 4000, .bounces = 2}, .reshootBudget = 100000});
  fresh.update(render::extractSnapshot(w, assets, 0), bvh, assets, {});
  EXPECT_EQ(differences(paths.vpls(), fresh.vpls()), 0) << "VPLs not where a fresh shot puts them";

  // And off again: the paths through the hole are blocked (Embree sees the solid fence).
  toggle(false);
  EXPECT_EQ(count(false).underHole, 0);
  paths.replace(render::extractSnapshot(w, assets, 0), bvh, assets);
  EXPECT_GT(count(true).onCut, 50);
  // Back where it started: the same pool, VPL for VPL.
  EXPECT_EQ(differences(paths.vpls(), before), 0) << "VPLs not back where they were";

  // A write that leaves the cut as it was (the colour) is a material change only.
  const ecs::Tick since = w.tick();
  w.advanceTick();
  w.write<Material>(fence.fence).baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  const gi::ChangeSet recolour = tracker.compute(w, assets, since);
  EXPECT_EQ(recolour.materials, std::vector<ecs::Entity>{fence.fence});
  EXPECT_TRUE(recolour.cutChanged.empty());
}
