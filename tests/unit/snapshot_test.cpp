// Extracting into a snapshot that held another frame must give what a fresh extraction gives, in the
// memory it already has.
#include <gtest/gtest.h>

#include <limits>
#include <set>

#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

using namespace dyngi;

namespace {
// `quads` mesh entities in a row, `lights` point lights, a camera when asked.
void fill(ecs::World& w, scene::AssetStore& a, int quads, int lights, bool camera) {
  const scene::MeshId quad = a.addMesh(scene::makeQuad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}));
  for (int i = 0; i < quads; ++i) {
    const ecs::Entity e = w.create();
    scene::Transform t;
    t.translation = {float(i), 0.0f, 0.0f};
    w.add(e, scene::WorldTransform{t.matrix()});
    w.add(e, scene::MeshInstance{quad, true});
    w.add(e, scene::Material{.baseColor = glm::vec4(0.1f * float(i), 0.5f, 0.5f, 1.0f)});
  }
  for (int i = 0; i < lights; ++i) {
    const ecs::Entity e = w.create();
    w.add(e, scene::WorldTransform{glm::mat4(1.0f)});
    w.add(e, scene::Light{.type = scene::LightType::Point, .intensity = 1.0f + float(i)});
  }
  if (camera) {
    const ecs::Entity e = w.create();
    scene::Transform t;
    t.translation = {0.0f, 1.0f, 5.0f};
    w.add(e, scene::WorldTransform{t.matrix()});
    w.add(e, scene::Camera{.yfov = 0.7f});
    w.add(e, scene::ActiveCamera{});
  }
}
}  // namespace

TEST(Snapshot, ExtractingIntoAnOldSnapshotGivesAFreshOneInItsMemory) {
  ecs::World big, small;
  scene::AssetStore bigAssets, smallAssets;
  fill(big, bigAssets, 6, 3, false);
  fill(small, smallAssets, 3, 1, true);
  render::RenderSnapshot reused = render::extractSnapshot(big, bigAssets, 7);
  ASSERT_EQ(reused.draws.size(), 6u);
  const render::DrawItem* memory = reused.draws.data();
  render::extractSnapshot(small, smallAssets, 9, reused);
  const render::RenderSnapshot fresh = render::extractSnapshot(small, smallAssets, 9);
  EXPECT_EQ(reused.draws.data(), memory) << "the draw list is rewritten in place";
  ASSERT_EQ(reused.draws.size(), fresh.draws.size());
  for (size_t i = 0; i < fresh.draws.size(); ++i) {
    EXPECT_EQ(reused.draws[i].entity, fresh.draws[i].entity);
    EXPECT_EQ(reused.draws[i].model, fresh.draws[i].model);
    EXPECT_EQ(reused.materialOf(reused.draws[i]), fresh.materialOf(fresh.draws[i]));
  }
  ASSERT_EQ(reused.lights.size(), fresh.lights.size());
  EXPECT_EQ(reused.lights[0].light.intensity, fresh.lights[0].light.intensity);
  EXPECT_EQ(reused.camera.view, fresh.camera.view);
  EXPECT_EQ(reused.camera.yfov, fresh.camera.yfov);
  EXPECT_EQ(reused.sceneBounds.min, fresh.sceneBounds.min);
  EXPECT_EQ(reused.sceneBounds.max, fresh.sceneBounds.max);
  EXPECT_EQ(reused.frame, 9u);
  EXPECT_EQ(reused.assets, &smallAssets);
  EXPECT_EQ(reused.skippedDraws, fresh.skippedDraws);
}

// A light or material component written directly, out of the content ranges, reaches lighting clamped
// into them, as the importer and the host API would have clamped it.
TEST(Snapshot, ComponentsOutOfContentRangeAreClampedIntoIt) {
  ecs::World w;
  scene::AssetStore a;
  const scene::MeshId quad = a.addMesh(scene::makeQuad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}));
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const ecs::Entity mesh = w.create();
  w.add(mesh, scene::WorldTransform{glm::mat4(1.0f)});
  w.add(mesh, scene::MeshInstance{quad, true});
  w.add(mesh, scene::Material{.baseColor = glm::vec4(2.0f, -1.0f, nan, 0.5f), .emissive = glm::vec3(inf, 1e30f, -3.0f), .metallic = nan, .roughness = 7.0f});
  const ecs::Entity light = w.create();
  w.add(light, scene::WorldTransform{glm::mat4(1.0f)});
  w.add(light, scene::Light{.type = scene::LightType::Spot, .color = glm::vec3(-1.0f, nan, 1e30f), .intensity = inf, .range = -2.0f,
                            .innerConeAngle = 1.2f, .outerConeAngle = 0.5f});
  const render::RenderSnapshot s = render::extractSnapshot(w, a, 0);
  ASSERT_EQ(s.draws.size(), 1u);
  ASSERT_EQ(s.lights.size(), 1u);
  const scene::Material& m = s.materialOf(s.draws[0]);
  EXPECT_EQ(m.baseColor, glm::vec4(1.0f, 0.0f, 1.0f, 0.5f));
  EXPECT_EQ(m.emissive, glm::vec3(scene::kMaxEmission, scene::kMaxEmission, 0.0f));
  EXPECT_EQ(m.metallic, 0.0f);
  EXPECT_EQ(m.roughness, 1.0f);
  const scene::Light& l = s.lights[0].light;
  EXPECT_EQ(l.color, glm::vec3(0.0f, 1.0f, scene::kMaxEmission));
  EXPECT_EQ(l.intensity, scene::kMaxLightIntensity);
  EXPECT_EQ(l.range, 0.0f);
  EXPECT_FLOAT_EQ(l.outerConeAngle, 0.5f);
  EXPECT_LT(l.innerConeAngle, l.outerConeAngle);
  EXPECT_GE(l.innerConeAngle, 0.0f);
}

// Each draw's material is its entity's component (or the default without one); instances that share a
// material share one entry, and distinct materials are never merged.
TEST(Snapshot, DrawsShareEqualMaterialsAndKeepTheirOwn) {
  for (const bool distinct : {false, true}) {
    ecs::World w;
    scene::AssetStore a;
    const scene::MeshId quad = a.addMesh(scene::makeQuad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}));
    std::vector<ecs::Entity> entities;
    for (int i = 0; i < 3000; ++i) {
      const ecs::Entity e = w.create();
      w.add(e, scene::WorldTransform{glm::translate(glm::mat4(1.0f), glm::vec3(float(i), 0.0f, 0.0f))});
      w.add(e, scene::MeshInstance{quad, true});
      if (i % 7 == 3) continue;  // no material: the default
      scene::Material m;
      m.roughness = distinct ? float(i) / 3000.0f : float(i % 3) * 0.25f;
      m.baseColor = glm::vec4(0.5f, 0.25f, distinct ? float(i % 2) : 0.5f, 1.0f);
      w.add(e, m);
    }
    const render::RenderSnapshot s = render::extractSnapshot(w, a, 0);
    ASSERT_EQ(s.draws.size(), 3000u);
    std::set<uint32_t> used;
    for (const render::DrawItem& d : s.draws) {
      const scene::Material* own = w.tryGet<scene::Material>(d.entity);
      EXPECT_EQ(s.materialOf(d), own ? *own : scene::Material{});
      used.insert(d.material);
    }
    EXPECT_EQ(s.materials.size(), used.size()) << "every entry is some draw's";
    if (!distinct) {
      EXPECT_EQ(s.materials.size(), 4u) << "three materials and the default";
    }
  }
}
