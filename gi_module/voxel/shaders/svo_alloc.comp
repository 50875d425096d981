#version 460
// SVO build, step 2 of a level: every flagged node of the level gets a group of 8 cleared children.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "subgroup_append.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) buffer Nodes { uint nodes[]; };
layout(set = 0, binding = 1) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = 2) buffer Counters { SvoCounters counters; };
layout(push_constant) uniform Push { uint level; };
void allocate(uint node) {
  bool want = nodes[node] == DYNGI_SVO_FLAG;  // not empty, not yet subdivided
  uint g;
  DYNGI_SUBGROUP_APPEND(counters.groups.x, want, g)
  if (!want) return;
  if (g >= counters.groups.y) {
    counters.groups.z = 1u;  // overflow: the node stays flagged without children (treated as occupied)
    return;
  }
  for (uint c = 0u; c < 8u; ++c) nodes[8u * g + c] = 0u;
  nodes[node] = DYNGI_SVO_FLAG | g;
}

void main() {
  uint n = levels[level].range.y, stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) allocate(levels[level].range.x + i);
}
