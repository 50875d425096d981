#version 460
// Energy beyond the last bounce (shared/bounce_tail.h): one workgroup sums the last gathered bounce's
// flux and its probes' (the bounce after it, never gathered), then scales the last bounce's VPLs by
// 1 / (1 - r) per channel so they carry every later bounce too.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "shared/bounce_tail.h"
layout(local_size_x = 256) in;
layout(set = 0, binding = DYNGI_VPL_TAIL_BINDING_VPLS) buffer Vpls { GpuVpl vpls[]; };
layout(push_constant) uniform Push { DYNGI_VPL_TAIL_PUSH };

shared vec3 lastSum[256];
shared vec3 nextSum[256];

void main() {
  uint t = gl_LocalInvocationID.x;
  vec3 last = vec3(0.0), next = vec3(0.0);
  for (uint i = t; i < count; i += 256u) {
    last += vpls[lastFirst + i].flux.rgb;         // invalid VPLs carry zero flux
    next += vpls[lastFirst + count + i].flux.rgb;  // the probe: that flux x the albedo it landed on
  }
  lastSum[t] = last;
  nextSum[t] = next;
  barrier();
  for (uint s = 128u; s > 0u; s >>= 1u) {
    if (t < s) {
      lastSum[t] += lastSum[t + s];
      nextSum[t] += nextSum[t + s];
    }
    barrier();
  }
  vec3 scale = bounceTailScale(lastSum[0], nextSum[0]);
  for (uint i = t; i < count; i += 256u) {
    vec3 flux = vpls[lastFirst + i].flux.rgb * scale;
    vpls[lastFirst + i].flux = vec4(flux, dot(flux, vec3(0.2126, 0.7152, 0.0722)));
  }
}
