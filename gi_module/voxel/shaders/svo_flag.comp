#version 460
// SVO build, step 1 of a fine level (below the coarse ones, see svo_mark.comp): every voxel fragment
// steps from the node it reached at the level above (kept per fragment, so a level costs one step rather
// than a descent; the first fine level descends from the root) to its child at `level`, and flags it.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "subgroup_append.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = 1) buffer Nodes { uint nodes[]; };
layout(set = 0, binding = 2) buffer Counters { SvoCounters counters; };
layout(set = 0, binding = 3) buffer FragmentNodes { uint fragmentNodes[]; };  // 0xFFFFFFFF: stopped
layout(push_constant) uniform Push { uint level; uint depth; uint firstLevel; };
void flagFragment(uint i) {
  uint c = fragments[i].x;
  if (c == DYNGI_VOXEL_EMPTY) return;
  uvec3 v = uvec3(c & 1023u, (c >> 10) & 1023u, (c >> 20) & 1023u);
  uint node = 0u;
  if (level == firstLevel) {
    for (uint l = 0u; l < level; ++l) {
      uint g = nodes[node] & DYNGI_SVO_GROUP_MASK;
      if (g == 0u) {  // an ancestor could not be subdivided (overflow): it stays flagged and childless
        fragmentNodes[i] = 0xFFFFFFFFu;
        return;
      }
      uint shift = depth - 1u - l;
      node = 8u * g + (((v.x >> shift) & 1u) | (((v.y >> shift) & 1u) << 1) | (((v.z >> shift) & 1u) << 2));
    }
  } else {
    uint parent = fragmentNodes[i];
    if (parent == 0xFFFFFFFFu) return;
    uint g = nodes[parent] & DYNGI_SVO_GROUP_MASK;
    if (g == 0u) {  // the parent could not be subdivided (overflow): it stays a flagged, childless node
      fragmentNodes[i] = 0xFFFFFFFFu;
      return;
    }
    uint shift = depth - level;
    node = 8u * g + (((v.x >> shift) & 1u) | (((v.y >> shift) & 1u) << 1) | (((v.z >> shift) & 1u) << 2));
  }
  fragmentNodes[i] = node;
  if ((nodes[node] & DYNGI_SVO_FLAG) != 0u) return;
  uint old = atomicOr(nodes[node], DYNGI_SVO_FLAG);
  bool newLeaf = level == depth && (old & DYNGI_SVO_FLAG) == 0u;
  uint unused;
  DYNGI_SUBGROUP_APPEND(counters.groups.w, newLeaf, unused)
}

void main() {
  uint n = min(counters.fragments.x, counters.fragments.y), stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < n; i += stride) flagFragment(i);
}
