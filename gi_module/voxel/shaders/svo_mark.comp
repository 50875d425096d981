#version 460
// SVO build, coarse levels: every voxel fragment marks the cells holding it in the dense occupancy
// pyramid of levels 0..coarse (see DYNGI_SVO_COARSE_LEVELS), finest first; a cell found marked already
// has its coarser cells marked (or being marked by the invocation that set it).
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = 1) readonly buffer Counters { SvoCounters counters; };
layout(set = 0, binding = 2) buffer Coarse { uint coarse[]; };
layout(push_constant) uniform Push { uint coarseLevels; uint depth; };  // finest coarse level, SVO depth

void markFragment(uint i) {
  uint c = fragments[i].x;
  if (c == DYNGI_VOXEL_EMPTY) return;
  uvec3 v = uvec3(c & 1023u, (c >> 10) & 1023u, (c >> 20) & 1023u);
  for (int l = int(coarseLevels); l >= 0; --l) {
    uvec3 cell = v >> (depth - uint(l));
    uint index = ((1u << (3u * uint(l))) - 1u) / 7u + cell.x + (cell.y << uint(l)) + (cell.z << (2u * uint(l)));
    uint bit = 1u << (index & 31u);
    if ((coarse[index >> 5] & bit) != 0u) return;
    atomicOr(coarse[index >> 5], bit);
  }
}

void main() {
  uint n = min(counters.fragments.x, counters.fragments.y), stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) markFragment(i);
}
