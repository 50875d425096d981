#version 460
// Energy beyond the last bounce (shared/bounce_tail.h): one workgroup sums the last simulated bounce's
// flux and its probes' (the bounce after it), then scales the probes by 1 / (1 - r) per channel: gathered
// as one more bounce, they carry that bounce and every later one, each assumed to light the scene as the
// probes' bounce does. (Scaling the last bounce instead, as the temporal technique does, assumes the
// later bounces light it as that bounce does: one bounce further from the truth. Cornell box, 3 bounces,
// against the path tracer with 8: the tall box's face to the red wall 1.137 -> 1.061; with 1 bounce the
// worst region 54 -> 17 percent off, the image 1.059 -> 0.984. It gathers a bounce more VPLs.)
#extension GL_GOOGLE_include_directive : require
#include "many_lights_shared.h"
#include "shared/bounce_tail.h"
layout(local_size_x = 256) in;
layout(set = 0, binding = DYNGI_VPL_TAIL_BINDING_VPLS) buffer Vpls { GpuVpl vpls[]; };
layout(push_constant) uniform Push { DYNGI_VPL_TAIL_PUSH };

shared vec3 lastSum[256];
shared vec3 nextSum[256];

void main() {
  uint t = gl_LocalInvocationID.x;
  vec3 last = vec3(0.0), next = vec3(0.0);
  for (uint i = t; i < count; i += 256u) last += vpls[lastFirst + i].flux.rgb;  // invalid VPLs carry zero flux
  // A probe: its VPL's flux x the albedo it landed on (x the run it stands for, vpl_bounce.comp).
  for (uint i = t; i < probes; i += 256u) next += vpls[lastFirst + count + i].flux.rgb;
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
  for (uint i = lastFirst + count + t; i < lastFirst + count + probes; i += 256u) {
    vec3 flux = vpls[i].flux.rgb * scale;
    vpls[i].flux = vec4(flux, dot(flux, vec3(0.2126, 0.7152, 0.0722)));
  }
}
