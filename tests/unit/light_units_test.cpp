// The CPU light formulas against hand-derived values (glTF KHR_lights_punctual recommendations).
#include <gtest/gtest.h>

#include <cmath>

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
