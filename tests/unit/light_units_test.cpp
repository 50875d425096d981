// The CPU light formulas against hand-derived values (glTF KHR_lights_punctual recommendations), and
// the lights' views.
#include <gtest/gtest.h>

#include <cmath>

#include "dyngi/engine/render/light_views.h"
#include "dyngi/engine/scene/light_units.h"

using namespace dyngi::scene;

TEST(LightUnits, PointLightIsInverseSquareWithCosine) {
  Light l;
  l.type = LightType::Point;
  l.intensity = 10.0f;
  l.color = {1, 0.5f, 0.25f};
  // Light 2 m above the point, surface facing up: E = I / d^2.
  glm::vec3 e = directIrradiance(l, {0, 2, 0}, {0, 0, -1}, {0, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(e.r, 10.0f / 4.0f, 1e-6f);
  EXPECT_NEAR(e.g, 0.5f * 10.0f / 4.0f, 1e-6f);
  // 60 degrees off the normal at distance 2: E = I cos(60) / 4.
  glm::vec3 p(0, 0, 0), lp = glm::vec3(std::sin(1.0471976f), std::cos(1.0471976f), 0) * 2.0f;
  EXPECT_NEAR(directIrradiance(l, lp, {0, 0, -1}, p, {0, 1, 0}).r, 10.0f * 0.5f / 4.0f, 1e-5f);
  // Behind the surface: nothing.
  EXPECT_EQ(directIrradiance(l, {0, -1, 0}, {0, 0, -1}, p, {0, 1, 0}).r, 0.0f);
}

TEST(LightUnits, SpotFalloffFollowsGltfRecommendation) {
  float inner = 0.3f, outer = 0.6f;
  EXPECT_FLOAT_EQ(spotFalloff(std::cos(0.1f), inner, outer), 1.0f);
  EXPECT_FLOAT_EQ(spotFalloff(std::cos(0.7f), inner, outer), 0.0f);
  float a = 0.45f;
  float t = (std::cos(a) - std::cos(outer)) / (std::cos(inner) - std::cos(outer));
  EXPECT_NEAR(spotFalloff(std::cos(a), inner, outer), t * t, 1e-6f);
  Light l;
  l.type = LightType::Spot;
  l.intensity = 4.0f;
  l.innerConeAngle = inner;
  l.outerConeAngle = outer;
  // Spot pointing down from (0,1,0); point at angle a off-axis on the floor.
  glm::vec3 p(std::tan(a), 0, 0);
  float d2 = 1.0f + p.x * p.x;
  float expected = 4.0f * std::cos(a) / d2 * t * t;
  EXPECT_NEAR(directIrradiance(l, {0, 1, 0}, {0, -1, 0}, p, {0, 1, 0}).r, expected, 1e-5f);
}

TEST(LightUnits, DirectionalAndRangeWindow) {
  Light d;
  d.type = LightType::Directional;
  d.intensity = 3.0f;
  glm::vec3 dir = glm::normalize(glm::vec3(1, -1, 0));
  EXPECT_NEAR(directIrradiance(d, {}, dir, {5, 5, 5}, {0, 1, 0}).r, 3.0f * std::sqrt(0.5f), 1e-5f);
  EXPECT_FLOAT_EQ(rangeWindow(5.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(rangeWindow(2.0f, 2.0f), 0.0f);
  float r = 0.5f;
  EXPECT_NEAR(rangeWindow(1.0f, 2.0f), (1 - r * r * r * r) * (1 - r * r * r * r), 1e-6f);
  Light off;
  off.enabled = false;
  EXPECT_EQ(directIrradiance(off, {0, 1, 0}, {0, -1, 0}, {}, {0, 1, 0}).r, 0.0f);
}

// A directional light's view over a window of a wide scene (a reflective shadow map near the camera):
// the window spans the view across the light, and every point of the scene, however far towards the
// light, lies within its depth range (it casts into the map).
TEST(LightViews, ADirectionalWindowSeesTheWholeSceneAlongTheLight) {
  dyngi::render::LightItem sun;
  sun.light.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.35f, -0.75f, 0.55f));
  Aabb scene;
  scene.min = {-200, 0, -20};
  scene.max = {200, 20, 20};
  const glm::vec3 c(112, 16, 48), half(64.0f / std::sqrt(3.0f));
  Aabb window;
  window.min = c - half;
  window.max = c + half;
  const auto views = dyngi::render::lightViews(sun, scene, &window);
  ASSERT_EQ(views.size(), 1u);
  const dyngi::render::LightView& v = views[0];
  EXPECT_TRUE(v.orthographic);
  EXPECT_NEAR(v.extent, 2.0f * 64.0f, 0.01f) << "the window's sphere across the light";
  const glm::vec4 centre = v.viewProj * glm::vec4(c, 1.0f);
  EXPECT_NEAR(centre.x, 0.0f, 1e-4f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-4f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? scene.max.x : scene.min.x, (i & 2) ? scene.max.y : scene.min.y, (i & 4) ? scene.max.z : scene.min.z);
    const glm::vec4 p = v.viewProj * glm::vec4(corner, 1.0f);
    EXPECT_GT(p.z, 0.0f) << "corner " << i;
    EXPECT_LT(p.z, 1.0f) << "corner " << i;
  }
  // Without a window: the whole scene across the light.
  EXPECT_NEAR(dyngi::render::lightViews(sun, scene)[0].extent, glm::length(scene.extent()), 0.01f);
}
