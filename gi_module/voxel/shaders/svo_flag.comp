#version 460
// SVO build, step 1 of a level: every voxel fragment walks down to `level` and flags the node it lands in.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = 1) buffer Nodes { uint nodes[]; };
layout(set = 0, binding = 2) buffer Counters { SvoCounters counters; };
layout(push_constant) uniform Push { uint level; uint depth; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(counters.fragments.x, counters.fragments.y)) return;
  uint c = fragments[i].x;
  if (c == DYNGI_VOXEL_EMPTY) return;
  uvec3 v = uvec3(c & 1023u, (c >> 10) & 1023u, (c >> 20) & 1023u);
  uint node = 0u;
  for (uint l = 0u; l < level; ++l) {
    uint g = nodes[node] & DYNGI_SVO_GROUP_MASK;
    if (g == 0u) return;  // the parent could not be subdivided (overflow)
    uint shift = depth - 1u - l;
    uint child = ((v.x >> shift) & 1u) | (((v.y >> shift) & 1u) << 1) | (((v.z >> shift) & 1u) << 2);
    node = 8u * g + child;
  }
  if ((nodes[node] & DYNGI_SVO_FLAG) != 0u) return;
  uint old = atomicOr(nodes[node], DYNGI_SVO_FLAG);
  if (level == depth && (old & DYNGI_SVO_FLAG) == 0u) atomicAdd(counters.groups.w, 1u);
}
