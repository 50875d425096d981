// Energy beyond the last simulated bounce, shared by C++ (both VPL techniques) and GLSL.
//
// VPLs simulate `bounces` bounces; the light of every later bounce is missing (a Cornell box with 3
// bounces is about 6% darker than with unlimited ones). Each further bounce keeps about the same
// fraction r of the flux as the one before, so the missing bounces sum to the last bounce's flux times
// r + r^2 + ... = r / (1 - r): the last bounce's VPLs carry it when their flux is scaled by 1 / (1 - r),
// per colour channel. r is measured, not assumed: each last-bounce VPL shoots one more cosine ray (a
// probe, never gathered), and r = sum(flux x albedo where the probe lands, 0 where it leaves the scene)
// / sum(flux). That is the scene's own reflectance seen from where the light is (an open scene loses
// more, a red room keeps more red). The missing bounces are assumed to light the scene the way the last
// one does: they are smoother still, so the error is small where the last bounce is already smooth.
// Many lights goes one bounce further (vpl_tail.comp): its probes land as VPLs of the next bounce, and
// those, scaled by 1 / (1 - r) and gathered, carry that bounce and the ones after it. The temporal
// technique's probes keep only the albedo they find, so it scales its last bounce.
#ifndef DYNGI_BOUNCE_TAIL_H
#define DYNGI_BOUNCE_TAIL_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gi::gpu {
using glm::vec3;
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

#ifdef __cplusplus
}  // namespace dyngi::gi::gpu
#endif
#endif
