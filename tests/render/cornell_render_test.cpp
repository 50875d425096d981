// The built-in Cornell box rendered with direct light only, checked against analytic truth.
#include <gtest/gtest.h>

#include <cmath>

#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/light_units.h"
#include "dyngi/engine/scene/transform_system.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;
using dyngi::sample::CornellLayout;

namespace {
constexpr float kPi = 3.14159265358979f;

struct CornellTruth {
  scene::Light light;
  glm::vec3 lightPos, lightDir;
  std::vector<Obb> boxes;
};

CornellTruth truthFrom(const render::RenderSnapshot& s, const scene::AssetStore& assets) {
  CornellTruth t;
  t.light = s.lights.at(0).light;
  t.lightPos = s.lights[0].position;
  t.lightDir = s.lights[0].direction;
  for (const auto& d : s.draws) {
    const auto& m = assets.mesh(d.mesh);
    if (m.name == "short_box" || m.name == "tall_box") t.boxes.push_back({d.model, m.bounds.extent() * 0.5f});
  }
  return t;
}

bool blocked(const CornellTruth& t, const glm::vec3& p, float margin) {
  for (const Obb& b : t.boxes)
    if (segmentHitsBox(p, t.lightPos, b, margin)) return true;
  return false;
}

class CornellRender : public RenderTest {
 protected:
  void SetUp() override {
    sample::buildBuiltinScene("cornell", world, assets);
    frame = render(world, assets, 256, 256);
    truth = truthFrom(frame.snapshot, assets);
    ASSERT_EQ(truth.boxes.size(), 2u);
  }
  ecs::World world;
  scene::AssetStore assets;
  Frame frame;
  CornellTruth truth;
};

bool isFloor(const glm::vec4& pos, const glm::vec4& n) { return pos.w > 0.5f && std::abs(pos.y) < 1e-3f && n.y > 0.99f; }
}  // namespace

TEST_F(CornellRender, RedLeftWallAndGreenRightWall) {
  int red = 0, redOk = 0, green = 0, greenOk = 0;
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const glm::vec4& p = frame.at(frame.position, x, y);
      const glm::vec4& l = frame.at(frame.hdr, x, y);
      const uint8_t* c = &frame.ldr[(size_t(y) * frame.width + x) * 4];
      // Skip empty pixels and ones too dim for 8-bit hue (the cone's fringe).
      if (p.w < 0.5f || l.r + l.g + l.b < 1e-3f || std::max({c[0], c[1], c[2]}) < 20) continue;
      const glm::vec4& n = frame.at(frame.normal, x, y);
      if (p.x < -0.999f && n.x > 0.99f) {
        ++red;
        redOk += c[0] > 2 * c[1] && c[0] > 2 * c[2];
        EXPECT_LT(x, frame.width / 2) << "red wall is on the left of the image";
      } else if (p.x > 0.999f && n.x < -0.99f) {
        ++green;
        greenOk += c[1] > 1.5 * c[0] && c[1] > 1.5 * c[2];
        EXPECT_GT(x, frame.width / 2) << "green wall is on the right of the image";
      }
    }
  ASSERT_GT(red, 500);
  ASSERT_GT(green, 500);
  EXPECT_GT(redOk, red * 99 / 100);
  EXPECT_GT(greenOk, green * 99 / 100);
}

TEST_F(CornellRender, FloorIrradianceMatchesAnalyticSpotFormula) {
  // Radiance of a Lambert floor is albedo/pi * E; invert it and compare E with the formula at the
  // pixel's world position. Points near a box shadow's edge are skipped (PCF softens them).
  double sumRel = 0, maxRel = 0;
  int n = 0;
  float peak = CornellLayout::kSpotIntensity / (CornellLayout::kSpotHeight * CornellLayout::kSpotHeight);
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const glm::vec4& p = frame.at(frame.position, x, y);
      if (!isFloor(p, frame.at(frame.normal, x, y))) continue;
      glm::vec3 wp(p);
      float e = scene::directIrradiance(truth.light, truth.lightPos, truth.lightDir, wp, {0, 1, 0}).r;
      if (e < 0.1f * peak || blocked(truth, wp, 0.06f)) continue;
      float measured = frame.at(frame.hdr, x, y).r * kPi / CornellLayout::kWhite;
      double rel = std::abs(measured - e) / e;
      sumRel += rel;
      maxRel = std::max(maxRel, rel);
      ++n;
    }
  ASSERT_GT(n, 2000) << "enough lit, unshadowed floor pixels";
  EXPECT_LT(sumRel / n, 0.01) << "mean relative error";
  EXPECT_LT(maxRel, 0.03) << "worst pixel within 3 percent";
}

TEST_F(CornellRender, ShadowedFloorIsDarkAndLitSpotIsBright) {
  int shadowed = 0, dark = 0;
  float centre = 0.0f, corner = 0.0f;
  int centreN = 0, cornerN = 0;
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const glm::vec4& p = frame.at(frame.position, x, y);
      if (!isFloor(p, frame.at(frame.normal, x, y))) continue;
      glm::vec3 wp(p);
      float e = scene::directIrradiance(truth.light, truth.lightPos, truth.lightDir, wp, {0, 1, 0}).r;
      float measured = frame.at(frame.hdr, x, y).r * kPi / CornellLayout::kWhite;
      if (e > 0.2f && blocked(truth, wp, -0.06f)) {  // well inside a box's shadow
        ++shadowed;
        dark += measured < 0.02f * e;
      }
      if (glm::length(glm::vec2(wp.x, wp.z) - glm::vec2(truth.lightPos.x, truth.lightPos.z)) < 0.15f && !blocked(truth, wp, 0.0f))
        centre += measured, ++centreN;
      if (std::abs(wp.x) > 0.85f && wp.z > 0.85f) corner += measured, ++cornerN;
    }
  ASSERT_GT(shadowed, 300);
  EXPECT_GT(dark, shadowed * 98 / 100) << "points the CPU says are occluded receive no direct light";
  ASSERT_GT(centreN, 20);
  ASSERT_GT(cornerN, 20);
  EXPECT_GT(centre / float(centreN), 3.0f * corner / float(cornerN)) << "the spot's pool of light is on the floor";
}

TEST_F(CornellRender, NothingAboveTheSpotConeIsLit) {
  // The spot points down with a 40 degree cone: the ceiling receives no direct light, and there is no
  // ambient term, so its radiance is exactly zero.
  int ceiling = 0;
  for (size_t i = 0; i < frame.position.size(); ++i) {
    if (frame.position[i].w > 0.5f && std::abs(frame.position[i].y - 2.0f) < 1e-3f) {
      ++ceiling;
      EXPECT_EQ(frame.hdr[i].r, 0.0f);
    }
  }
  EXPECT_GT(ceiling, 100);
}

// The shadow map is kept while no light view and no caster changed, and redrawn (only the layers that
// need it) when something did: each frame must equal what a fresh renderer draws for the same snapshot.
TEST_F(RenderTest, ShadowMapIsKeptWhileNothingMovesAndRedrawnWhenSomethingDoes) {
  ecs::World world;
  scene::AssetStore assets;
  sample::buildBuiltinScene("cornell", world, assets);
  ecs::Scheduler scheduler;
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  render::Renderer renderer(context());
  renderer.resize(96, 96);
  uint64_t frameIndex = 0;
  auto step = [&] {
    scheduler.runFrame(world, ecs::FrameTime{1.0 / 60, double(frameIndex) / 60, frameIndex});
    render::RenderSnapshot s = render::extractSnapshot(world, assets, frameIndex++);
    renderer.render(s);
    bool drewShadows = false;
    for (const auto& [name, ms] : renderer.lastStats().gpuMs) drewShadows |= name == "shadow";
    // The same snapshot through a renderer that has never seen a frame.
    render::Renderer fresh(context());
    fresh.resize(96, 96);
    fresh.render(s);
    double rel = render::relativeMse(renderer.readback(render::TargetId::Hdr), fresh.readback(render::TargetId::Hdr));
    return std::pair{drewShadows, rel};
  };
  auto named = [&](const std::string& n) {
    ecs::Entity found{};
    world.each<scene::Name>([&](ecs::Entity e, const scene::Name& nm) { if (nm.value == n) found = e; });
    return found;
  };
  auto [first, rel0] = step();
  EXPECT_TRUE(first);
  EXPECT_LT(rel0, 1e-12);
  auto [still, rel1] = step();
  EXPECT_FALSE(still) << "nothing moved: the shadow map is kept";
  EXPECT_LT(rel1, 1e-12);
  world.write<scene::Transform>(named("tall_box")).translation.x += 0.2f;
  auto [boxMoved, rel2] = step();
  EXPECT_TRUE(boxMoved);
  EXPECT_LT(rel2, 1e-12) << "the moved box's shadow moved with it";
  world.write<scene::Transform>(named("spot")).translation.z += 0.1f;
  auto [lightMoved, rel3] = step();
  EXPECT_TRUE(lightMoved);
  EXPECT_LT(rel3, 1e-12) << "the moved light's shadow map was redrawn";
  auto [stillAgain, rel4] = step();
  EXPECT_FALSE(stillAgain);
  EXPECT_LT(rel4, 1e-12);
  // A box that keeps moving under a still light: the layer is the cached static casters plus the box;
  // then the light moves too (drawn whole), then stops (the cache is redrawn for the new view).
  for (int f = 0; f < 8; ++f) {
    world.write<scene::Transform>(named("short_box")).translation.z += 0.03f;
    if (f >= 3 && f < 5) world.write<scene::Transform>(named("spot")).translation.x += 0.05f;
    auto [drew, rel] = step();
    EXPECT_TRUE(drew);
    EXPECT_LT(rel, 1e-12) << "moving box, frame " << f;
  }
  // A long jump of the moving box under the still light: only the texels it covered and covers are
  // restored from the cache, and nothing of its old shadow may stay behind.
  world.write<scene::Transform>(named("short_box")).translation.x -= 0.6f;
  auto [jumped, relJump] = step();
  EXPECT_TRUE(jumped);
  EXPECT_LT(relJump, 1e-12) << "the jumped box left its old shadow behind";
  // A point light switched in mid-run needs six more layers: the shadow map grows and every layer is
  // drawn again, the spot's included.
  ecs::Entity bulb = world.create();
  scene::Transform bt{.translation = glm::vec3(0.4f, 1.4f, 0.3f)};
  world.add(bulb, bt);
  world.add(bulb, scene::WorldTransform{bt.matrix()});
  world.add(bulb, scene::Light{.type = scene::LightType::Point, .color = glm::vec3(1.0f, 0.8f, 0.6f), .intensity = 0.5f});
  auto [grew, rel5] = step();
  EXPECT_TRUE(grew);
  EXPECT_LT(rel5, 1e-12) << "a point light added: shadow layers grown";
  auto [stillWithBulb, rel6] = step();
  EXPECT_FALSE(stillWithBulb);
  EXPECT_LT(rel6, 1e-12);
}
