#version 460
// Tests only: one cone per ray (origin and direction in voxel units), through vctCone, so the GPU march
// can be held equal to its C++ twin (gi::vctConeCpu). Results: rgb radiance, a opacity.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
layout(local_size_x = 64) in;
layout(constant_id = 0) const bool kAnisotropic = false;
layout(set = 0, binding = DYNGI_VCT_PROBE_BINDING_RAYS) readonly buffer Rays { vec4 rays[]; };  // origin, direction pairs
layout(set = 0, binding = DYNGI_VCT_PROBE_BINDING_RADIANCE) uniform sampler3D vctRadiance;
layout(set = 0, binding = DYNGI_VCT_PROBE_BINDING_ANISO) uniform sampler3D vctAniso;
layout(set = 0, binding = DYNGI_VCT_PROBE_BINDING_RESULTS) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { DYNGI_VCT_PROBE_PUSH };
#include "vct_cone.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  float occ;
  vec4 r = vctCone(rays[2u * i].xyz, normalize(rays[2u * i + 1u].xyz), tanHalf, 1.0, maxDistance, farNarrowing, occ);
  results[i] = r;
}
