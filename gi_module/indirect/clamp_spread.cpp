#include "indirect/clamp_spread.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/clamp_spread.h"

namespace dyngi::gi {
namespace {
constexpr double kPi = 3.14159265358979323846;

// J(a, b) = integral_0^2pi max(0, a cos phi + b) dphi, a >= 0.
double lobeAround(double a, double b) {
  if (a <= std::abs(b)) return b > 0.0 ? 2.0 * kPi * b : 0.0;
  const double phi0 = std::acos(-b / a);
  return 2.0 * (a * std::sin(phi0) + b * phi0);
}

// I and N (shaders/shared/clamp_spread.h) by the midpoint rule in t, u = U t^2: the integrand of I
// peaks within eta of u = 0, and the square root mapping puts most samples there.
glm::vec2 integrate(double eta, double c) {
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c)), U = std::sqrt(std::max(0.0, 1.0 - eta * eta));
  constexpr int kSamples = 2048;
  double lost = 0.0, norm = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double t = (k + 0.5) / kSamples, u = U * t * t, du = 2.0 * U * t / kSamples;
    const double q = u * u + eta * eta, j = lobeAround(s * u, c * eta);
    if (q > 0.0) lost += eta * u * (1.0 / q - 1.0) / q * j * du;
    norm += (1.0 - q) * j * u * du;
  }
  // On the plane (eta -> 0) the integrand of I narrows to a spike at u = 0 that no quadrature holds; its
  // limit is all the light the VPL's cosine lobe sends into the half-space, pi (1 + c) / 2.
  if (eta == 0.0) lost = kPi * (1.0 + c) / 2.0;
  return {float(lost), float(norm)};
}
}  // namespace

const std::vector<glm::vec2>& clampSpreadTable() {
  static const std::vector<glm::vec2> table = [] {
    const int E = DYNGI_CLAMP_SPREAD_ETA_CELLS, C = DYNGI_CLAMP_SPREAD_COS_CELLS;
    std::vector<glm::vec2> t(size_t(E) * C);
    for (int ci = 0; ci < C; ++ci)
      for (int ei = 0; ei < E; ++ei) t[size_t(ei + E * ci)] = integrate(double(ei) / (E - 1), -1.0 + 2.0 * double(ci) / (C - 1));
    return t;
  }();
  return table;
}

glm::vec2 clampSpreadLookup(const std::vector<glm::vec2>& table, float eta, float c) {
  const int E = DYNGI_CLAMP_SPREAD_ETA_CELLS, C = DYNGI_CLAMP_SPREAD_COS_CELLS;
  const glm::vec2 p = gpu::clampSpreadCoords(eta, c);
  const int e0 = std::min(int(p.x), E - 2), c0 = std::min(int(p.y), C - 2);
  const float fe = p.x - float(e0), fc = p.y - float(c0);
  auto at = [&](int e, int ci) { return table[size_t(e + E * ci)]; };
  return glm::mix(glm::mix(at(e0, c0), at(e0 + 1, c0), fe), glm::mix(at(e0, c0 + 1), at(e0 + 1, c0 + 1), fe), fc);
}

}  // namespace dyngi::gi
