#pragma once
// Small Monte Carlo helpers shared by the path tracer and the VPL shooter (CPU).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace dyngi::gi {

// SplitMix64 finaliser: turns any 64-bit value into a well-mixed one (seeding, hashing).
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Point i of the R3 low-discrepancy sequence (Roberts 2018, "The unreasonable effectiveness of
// quasirandom sequences"): fract(offset + i alpha), alpha_k = phi_3^-k with phi_3 the real root of
// x^4 = x + 1. Any run of consecutive indices is evenly spread over the cube, whatever its start, and so
// are its 2D projections; `offset` (a Cranley-Patterson rotation) makes a seed's own sequence.
inline glm::vec3 r3Point(uint64_t i, const glm::vec3& offset) {
  constexpr double a1 = 0.8191725133961645, a2 = 0.6710436067037893, a3 = 0.5497004779019703;
  const double k = double(i);
  auto frac = [](double v) { return float(v - std::floor(v)); };
  return {frac(offset.x + k * a1), frac(offset.y + k * a2), frac(offset.z + k * a3)};
}

// Two unit vectors completing n to an orthonormal basis.
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& b1, glm::vec3& b2) {
  glm::vec3 t = std::abs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  b1 = glm::normalize(glm::cross(n, t));
  b2 = glm::cross(n, b1);
}

// Cosine-distributed direction around unit n from two uniform numbers in [0, 1).
inline glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2) {
  glm::vec3 b1, b2;
  orthonormalBasis(n, b1, b2);
  float r = std::sqrt(u1), phi = 6.28318530718f * u2;
  return glm::normalize(r * std::cos(phi) * b1 + r * std::sin(phi) * b2 + std::sqrt(std::max(0.0f, 1.0f - u1)) * n);
}

}  // namespace dyngi::gi
