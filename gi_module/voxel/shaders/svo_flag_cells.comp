#version 460
// SVO build, step 1 of a coarse level: every marked cell of the occupancy pyramid at `level` walks down
// from the root (its ancestors were flagged and subdivided by the levels before) and flags its node.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Coarse { uint coarse[]; };
layout(set = 0, binding = 1) buffer Nodes { uint nodes[]; };
layout(push_constant) uniform Push { uint level; };

void flagCell(uint i) {
  uint index = ((1u << (3u * level)) - 1u) / 7u + i;
  if ((coarse[index >> 5] & (1u << (index & 31u))) == 0u) return;
  uint mask = (1u << level) - 1u;
  uvec3 cell = uvec3(i & mask, (i >> level) & mask, i >> (2u * level));
  uint node = 0u;
  for (uint l = 0u; l < level; ++l) {
    uint g = nodes[node] & DYNGI_SVO_GROUP_MASK;
    if (g == 0u) return;  // the parent could not be subdivided (overflow)
    uint shift = level - 1u - l;
    node = 8u * g + (((cell.x >> shift) & 1u) | (((cell.y >> shift) & 1u) << 1) | (((cell.z >> shift) & 1u) << 2));
  }
  atomicOr(nodes[node], DYNGI_SVO_FLAG);
}

void main() {
  uint n = 1u << (3u * level), stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) flagCell(i);
}
