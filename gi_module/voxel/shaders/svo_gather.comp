#version 460
// SVO build, step 0: gather the valid fragments of every entity's range (ranges have slack and holes)
// into one dense list, so the per-level passes touch only real fragments.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = 1) writeonly buffer Dense { uvec4 dense[]; };
layout(set = 0, binding = 2) buffer Counters { SvoCounters counters; };
layout(push_constant) uniform Push { uint slots; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= slots) return;
  uvec4 f = fragments[i];
  if (f.x == DYNGI_VOXEL_EMPTY) return;
  uint j = atomicAdd(counters.fragments.x, 1u);
  if (j < counters.fragments.y) dense[j] = f;
}
