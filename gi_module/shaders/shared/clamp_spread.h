// The distance clamp's lost light, spread near where it lands, shared by C++ and GLSL.
//
// The gather's G = cos_x cos_y / max(B, d^2) drops, for a VPL y closer than sqrt(B) to the receiver x,
// the part cos_x cos_y (1 / d^2 - 1 / B): the singular spike that makes hot spots, and with it the light
// corners should get (a VPL on the floor by a wall sends half its flux into the wall within sqrt(B) of
// itself; the clamp keeps little of it). Here that light is given back, spread smoothly near where it
// lands. Take the receiver's surface as the plane through x with normal n_x, y at height h above it and
// its normal at c = -n_y . n_x. In units of sqrt(B) (eta = h / sqrt(B), u the distance along the plane
// from y's foot) the light the clamp drops over the whole plane is, per unit flux / pi,
//   I(eta, c) = integral over the plane of cos_x cos_y (1 / d^2 - 1 / B) dA
//             = integral_0^sqrt(1 - eta^2) eta u (1 / q - 1) / q J(s u, c eta) du,  q = u^2 + eta^2,
// with s = sqrt(1 - c^2) and J(a, b) = integral_0^2pi max(0, a cos phi + b) dphi (dimensionless: B
// cancels). At eta -> 0 it is pi (1 + c) / 2, all the light the lobe sends into the plane: pi for a VPL
// facing the plane, pi / 2 for one perpendicular to it, 0 for one facing away (clampSpreadTable sets
// that row, which no quadrature reaches). It is laid on the plane with the kernel
//   w = max(0, n_y . (x - y)) / sqrt(B) max(0, 1 - d^2 / B) / (B N(eta, c)),
//   N(eta, c) = integral_0^sqrt(1 - eta^2) (1 - q) J(s u, c eta) u du,
// which integrates to 1 over the plane: the VPL's cosine lobe times a bump that falls to 0 at d = sqrt(B),
// so it lands on the side the VPL faces, within the clamp's reach. The gather adds to G
//   I w = (I / N) cos_y sqrt(d^2 / B) max(0, 1 - d^2 / B) / B
// (n_y . (x - y) = cos_y d), visible as the VPL is. On a plane every receiver sees the same eta and c,
// so the light given back is exactly the light dropped; where the surface ends within reach (a box's
// edge) the part of the kernel past it is lost. The plane is also taken to run on past the receiver:
// a VPL on the floor beside a box sits on the box face's plane extended, and its light, dropped where
// that plane is not, would land on the face. The gather gives back nothing where the screen shows
// something other than the plane at the VPL's foot (spreadPlaneShown in gather.glsl).
// Stretched along the corner. Each VPL's dropped light is a bump of its own, and with 512-1024 VPLs in
// a room the bumps stand apart along the walls' bases as blobs. Stretching the bump by A along t, the
// line where the VPL's plane meets the receiver's (t = n_x x n_y; the lobe does not change along it),
// merges neighbours along the corner, where their light belongs, without moving it away from the corner:
// the bump becomes max(0, 1 - (d^2 - a^2) / B - a^2 / (A^2 B)) with a = (x - y) . t, and its integral is
// A N (substitute a = A v). A is A_max (VplOptions::clampSpread) for a VPL perpendicular to the plane
// and falls to 1 as it faces it (A = 1 + (A_max - 1) s^2: t is undefined there). A wider round bump
// (the first version) moved the light off the corners instead (docs/QUALITY.md). The table holds I and N
// (both smooth, unlike their ratio, which grows as 1 / eta for c -> 1), computed once on the CPU
// (clampSpreadTable, gi_module/indirect/clamp_spread.cpp).
#ifndef DYNGI_CLAMP_SPREAD_H
#define DYNGI_CLAMP_SPREAD_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gi::gpu {
using glm::clamp;
using glm::max;
using glm::sqrt;
using glm::vec2;
#define DYNGI_SHARED_FN inline
#else
#define DYNGI_SHARED_FN
#endif

// Table of (I, N): eta in [0, 1] over ETA_CELLS samples, c in [-1, 1] over COS_CELLS; entry
// eta_index + ETA_CELLS * c_index.
#define DYNGI_CLAMP_SPREAD_ETA_CELLS 33
#define DYNGI_CLAMP_SPREAD_COS_CELLS 33

// The table's continuous coordinates of (eta, c), for bilinear interpolation between samples.
DYNGI_SHARED_FN vec2 clampSpreadCoords(float eta, float c) {
  return vec2(clamp(eta, 0.0f, 1.0f) * float(DYNGI_CLAMP_SPREAD_ETA_CELLS - 1),
              clamp(0.5f * (c + 1.0f), 0.0f, 1.0f) * float(DYNGI_CLAMP_SPREAD_COS_CELLS - 1));
}

// The stretch along t for a VPL at c = -n_y . n_x (maxStretch: VplOptions::clampSpread).
DYNGI_SHARED_FN float clampSpreadStretch(float c, float maxStretch) { return 1.0f + (maxStretch - 1.0f) * max(0.0f, 1.0f - c * c); }

// The stretched bump at a receiver d2 from the VPL, along2 = ((x - y) . t)^2 of it along t: 0 outside the
// ellipse it covers (the gather looks up the table only inside).
DYNGI_SHARED_FN float clampSpreadBump(float d2, float along2, float B, float stretch) {
  return max(0.0f, 1.0f - (d2 - along2) / B - along2 / (B * stretch * stretch));
}

// What the gather adds to G for a VPL at distance^2 d2 with cos_y, given (I, N) at its (h / sqrt(B), c)
// and the bump there.
DYNGI_SHARED_FN float clampSpreadG(vec2 lostAndNorm, float bump, float d2, float cosY, float B, float stretch) {
  return lostAndNorm.y > 0.0f ? lostAndNorm.x / (stretch * lostAndNorm.y) * cosY * sqrt(d2 / B) * bump / B : 0.0f;
}

#ifdef __cplusplus
}  // namespace dyngi::gi::gpu
#endif
#endif
