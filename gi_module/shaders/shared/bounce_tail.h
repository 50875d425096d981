// Energy beyond the last simulated bounce, shared by C++ (both VPL techniques) and GLSL.
//
// VPLs simulate `bounces` bounces; the light of every later bounce is missing (a Cornell box with 3
// bounces is about 6% darker than with unlimited ones). Each further bounce keeps about the same
// fraction r of the flux as the one before, so the missing bounces sum to the next bounce's flux times
// 1 + r + r^2 + ... = 1 / (1 - r), per colour channel. r is measured, not assumed: each last-bounce VPL
// shoots one more cosine ray (a probe), and r = sum(flux x albedo where the probe lands, 0 where it
// leaves the scene) / sum(flux). That is the scene's own reflectance seen from where the light is (an
// open scene loses more, a red room keeps more red). The probes are the next bounce's VPLs (where they
// land, flux x albedo there): scaled by 1 / (1 - r) and gathered, they carry that bounce and every later
// one, which are assumed to light the scene the way the first of them does (they are smoother still).
// Both VPL techniques do that: many lights in vpl_tail.comp, the temporal technique when it uploads a
// set (TemporalIndirect::prepare). Scaling the last bounce instead (what both did first) lays the later
// bounces one bounce earlier, where faces that only later bounces reach are wrong by tens of percent.
#ifndef DYNGI_BOUNCE_TAIL_H
#define DYNGI_BOUNCE_TAIL_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstdint>
namespace dyngi::gi::gpu {
using glm::vec3;
using uint = uint32_t;
#define DYNGI_SHARED_FN inline
#else
#define DYNGI_SHARED_FN
#endif

// r is held below this, so a closed white room (r -> 1) cannot make the tail unbounded; the scale is
// then at most 1 / (1 - 0.9) = 10.
#define DYNGI_BOUNCE_TAIL_MAX_RATIO 0.9f

// lastFlux: the last bounce's summed flux; nextFlux: what its probes found (flux x albedo summed).
DYNGI_SHARED_FN vec3 bounceTailScale(vec3 lastFlux, vec3 nextFlux) {
  vec3 r = nextFlux / max(lastFlux, vec3(1e-30f));
  r = clamp(r, vec3(0.0f), vec3(DYNGI_BOUNCE_TAIL_MAX_RATIO));
  return vec3(1.0f) / (vec3(1.0f) - r);
}

// A stride s (VplOptions::bounceTailStride) gathers one probe in each run of s consecutive last-bounce
// VPLs of `count`, its flux x the run's length: the choice within a run is a hash of the run, not its
// first, because the VPLs follow low-discrepancy sequences whose even points lie in one half of the domain.
DYNGI_SHARED_FN uint bounceTailRunLength(uint run, uint stride, uint count) {
  return count - run * stride < stride ? count - run * stride : stride;
}
DYNGI_SHARED_FN uint bounceTailChosenInRun(uint run, uint stride, uint count) {
  uint x = run * 0x9E3779B9u + 0x7F4A7C15u;
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return run * stride + x % bounceTailRunLength(run, stride, count);
}

#ifdef __cplusplus
}  // namespace dyngi::gi::gpu
#endif
#endif
