#version 460
// SVO build, step 0: gather the valid fragments of every entity's range (ranges have slack and holes)
// into one dense list, so the per-level passes touch only real fragments.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "subgroup_append.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = 1) writeonly buffer Dense { uvec4 dense[]; };
layout(set = 0, binding = 2) buffer Counters { SvoCounters counters; };
layout(push_constant) uniform Push { uint slots; };
void gatherSlot(uint i) {
  uvec4 f = fragments[i];
  bool valid = f.x != DYNGI_VOXEL_EMPTY;
  uint j;
  DYNGI_SUBGROUP_APPEND(counters.fragments.x, valid, j)
  if (valid && j < counters.fragments.y) dense[j] = f;
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < slots; i += stride) gatherSlot(i);
}
