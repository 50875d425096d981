// Point (cube shadow map) and directional lights over a floor, against the analytic formulas and a
// CPU ray/box visibility test.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/scene/light_units.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kAlbedo = 0.5f;

struct FloorScene {
  ecs::World world;
  scene::AssetStore assets;
  Obb box;
  scene::Light light;
  glm::vec3 lightPos{0.0f}, lightDir{0, -1, 0};

  explicit FloorScene(scene::LightType type) {
    using namespace scene;
    auto add = [&](MeshData mesh, const Transform& t) {
      Entity e = world.create();
      world.add(e, t);
      world.add(e, MeshInstance{assets.addMesh(std::move(mesh)), true});
      world.add(e, Material{.baseColor = glm::vec4(kAlbedo, kAlbedo, kAlbedo, 1.0f)});
    };
    add(makeQuad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}), {});
    Transform bt;
    bt.translation = {0.4f, 0.25f, 0.2f};
    bt.rotation = glm::angleAxis(0.4f, glm::vec3(0, 1, 0));
    add(makeBox(glm::vec3(0.25f)), bt);
    box = {bt.matrix(), glm::vec3(0.25f)};

    light.type = type;
    Transform lt;
    if (type == LightType::Point) {
      light.intensity = 5.0f;
      lightPos = {-0.1f, 1.4f, -0.3f};
      lt.translation = lightPos;
    } else {
      light.intensity = 2.0f;
      lightDir = glm::normalize(glm::vec3(0.6f, -1.0f, 0.3f));
      lt.rotation = glm::quatLookAtRH(lightDir, glm::vec3(0, 1, 0));
      lightPos = -lightDir * 50.0f;  // for the CPU shadow ray only
    }
    Entity l = world.create();
    world.add(l, lt);
    world.add(l, light);

    Entity cam = world.create();
    Transform ct;
    ct.translation = {0.0f, 4.0f, 3.0f};
    ct.rotation = glm::quatLookAtRH(glm::normalize(glm::vec3(0, -4.0f, -3.0f)), glm::vec3(0, 1, 0));
    world.add(cam, ct);
    world.add(cam, Camera{.yfov = 0.9f});
    world.add(cam, ActiveCamera{});
  }
};

class AnalyticLights : public RenderTest, public ::testing::WithParamInterface<scene::LightType> {};
}  // namespace

TEST_P(AnalyticLights, FloorMatchesFormulaAndShadowsMatchRayTest) {
  FloorScene s(GetParam());
  Frame f = render(s.world, s.assets, 256, 256);
  int lit = 0, shadowed = 0, dark = 0;
  double sumRel = 0, maxRel = 0;
  for (size_t i = 0; i < f.position.size(); ++i) {
    const glm::vec4& p = f.position[i];
    if (p.w < 0.5f || std::abs(p.y) > 1e-3f || f.normal[i].y < 0.99f) continue;
    glm::vec3 wp(p);
    float e = scene::directIrradiance(s.light, s.lightPos, s.lightDir, wp, {0, 1, 0}).r;
    if (e < 0.05f * s.light.intensity) continue;
    float measured = f.hdr[i].r * kPi / kAlbedo;
    if (!segmentHitsBox(wp, s.lightPos, s.box, 0.05f)) {
      double rel = std::abs(measured - e) / e;
      sumRel += rel;
      maxRel = std::max(maxRel, rel);
      ++lit;
    } else if (segmentHitsBox(wp, s.lightPos, s.box, -0.05f)) {
      ++shadowed;
      dark += measured < 0.02f * e;
    }
  }
  ASSERT_GT(lit, 3000);
  EXPECT_LT(sumRel / lit, 0.01);
  EXPECT_LT(maxRel, 0.03);
  ASSERT_GT(shadowed, 200) << "the box casts a visible shadow";
  EXPECT_GT(dark, shadowed * 98 / 100);
}

INSTANTIATE_TEST_SUITE_P(Lights, AnalyticLights, ::testing::Values(scene::LightType::Point, scene::LightType::Directional),
                         [](const auto& param) { return param.param == scene::LightType::Point ? "Point" : "Directional"; });
