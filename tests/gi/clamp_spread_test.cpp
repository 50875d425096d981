// The clamp spread (gi_module/shaders/shared/clamp_spread.h) against brute force: on a plane, the light a
// VPL gives with the clamp and its spread is the light it gives without the clamp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/report.h"
#include "indirect/clamp_spread.h"
#include "shaders/shared/clamp_spread.h"

using namespace dyngi;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Sum over the plane z = 0 (a square of half-side `half`, n x n cells, receivers facing +z) of the
// gather's G for a VPL at height h with normal (s, 0, -c), times the cell's area: the light it gives
// the plane, per unit flux / pi. clamp: B (0: none); spread: VplOptions::clampSpread (0: none).
double lightOnPlane(const std::vector<glm::vec2>& table, double h, double c, double B, double spread, double half, int n) {
  const glm::dvec3 y(0.0, 0.0, h), ny(std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, -c);
  const double cell = 2.0 * half / n;
  const float stretch = gi::gpu::clampSpreadStretch(float(c), float(spread));
  const glm::dvec3 t = glm::cross(glm::dvec3(0.0, 0.0, 1.0), ny);  // along both planes
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 x(-half + (i + 0.5) * cell, -half + (j + 0.5) * cell, 0.0);
      const glm::dvec3 d = y - x;
      const double d2 = glm::dot(d, d), dist = std::sqrt(d2);
      const double cx = d.z / dist, cy = -glm::dot(ny, d) / dist;
      if (cx <= 0.0 || cy <= 0.0) continue;
      double g = cx * cy / std::max(B, d2);
      if (spread > 0.0) {
        const double along = glm::dot(d, t), along2 = along * along / std::max(glm::dot(t, t), 1e-8);
        const float bump = gi::gpu::clampSpreadBump(float(d2), float(along2), float(B), stretch);
        const glm::vec2 lostAndNorm = gi::clampSpreadLookup(table, float(cx * dist / std::sqrt(B)), float(c));
        g += gi::gpu::clampSpreadG(lostAndNorm, bump, float(d2), float(cy), float(B), stretch);
      }
      sum += g * cell * cell;
    }
  return sum;
}
}  // namespace

// A VPL facing the plane, tilted, perpendicular (a floor VPL by a wall) and turned half away, close to it
// and at half the clamp's reach: the clamp alone drops most of its light there; with the spread (round,
// and stretched 4 times along the corner) the plane gets what it gets without any clamp, within a percent.
TEST(ClampSpread, GivesBackOnAPlaneWhatTheClampDrops) {
  const std::vector<glm::vec2>& table = gi::clampSpreadTable();
  const double B = 0.01, half = 0.4;
  for (double c : {1.0, 0.6, 0.0, -0.4})
    for (double h : {0.005, 0.02, 0.05})
      for (double spread : {1.0, 4.0}) {
        const int n = 1600;  // 0.5 mm cells: h = 5 mm is resolved
        const double exact = lightOnPlane(table, h, c, 0.0, 0.0, half, n);
        const double clamped = lightOnPlane(table, h, c, B, 0.0, half, n);
        const double spreadBack = lightOnPlane(table, h, c, B, spread, half, n);
        dyngi::test::report("c %+.1f h %.3f stretch %.0f: unclamped %.4f, clamped %.4f, with the spread %.4f\n", c, h, spread, exact, clamped,
                    spreadBack);
        EXPECT_NEAR(spreadBack / exact, 1.0, 0.01) << "c " << c << " h " << h << " stretch " << spread;
        if (c >= 0.0 && h < 0.03) {
          EXPECT_LT(clamped / exact, 0.9) << "the clamp must drop light here for the check to mean anything";
        }
      }
}

// The table's limits: a VPL on the plane loses all the light its lobe sends into it, pi (1 + c) / 2 (all
// of pi facing it, half perpendicular, none facing away), and the first sample off the plane is close to
// that (a table row left at 0 there would halve the light of VPLs within a few millimetres); nothing is
// lost from sqrt(B) away.
TEST(ClampSpread, TableHasTheAnalyticLimits) {
  const std::vector<glm::vec2>& table = gi::clampSpreadTable();
  const float firstSample = 1.0f / float(DYNGI_CLAMP_SPREAD_ETA_CELLS - 1);
  for (float c : {1.0f, 0.5f, 0.0f, -0.5f, -1.0f}) {
    const double limit = kPi * (1.0 + c) / 2.0;
    EXPECT_NEAR(gi::clampSpreadLookup(table, 0.0f, c).x, limit, 1e-4) << c;
    EXPECT_NEAR(gi::clampSpreadLookup(table, firstSample, c).x, limit, 0.07 * kPi) << c;
    EXPECT_NEAR(gi::clampSpreadLookup(table, 1.0f, c).x, 0.0, 1e-6) << c;
  }
}
