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
