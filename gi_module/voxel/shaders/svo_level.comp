#version 460
// SVO build bookkeeping (one thread): before level `level`'s expand pass, fix that level's node range
// from the groups the previous level allocated, remember the group counter, and write the indirect
// dispatch size of the expand pass. Level 0 also seeds the root from the occupancy pyramid; the leaf level
// (depth) writes the leaf list's header.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
layout(local_size_x = 1) in;
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_LEVELS) buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_COUNTERS) buffer Counters { SvoCounters counters; };
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_NODES) buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_NODE_CELLS) buffer NodeCells { uint nodeCells[]; };
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_OCCUPANCY) readonly buffer Occupancy { uint occupancy[]; };
layout(set = 0, binding = DYNGI_SVO_LEVEL_BINDING_LEAF_LIST) buffer LeafList { uint leafList[]; };
layout(push_constant) uniform Push { DYNGI_SVO_LEVEL_PUSH };
void main() {
  uint used = min(counters.groups.x, counters.groups.y);
  if (level == 0u) {
    levels[0].range = uvec4(0u, 1u, used, 0u);
    nodes[0] = (occupancy[0] & 1u) != 0u ? DYNGI_SVO_FLAG : 0u;  // level 0's one cell
    nodeCells[0] = 0u;
  } else {
    uint before = levels[level - 1u].range.z;
    levels[level].range = uvec4(8u * before, 8u * (used - before), used, 0u);
  }
  const uint perGroup = 64u * DYNGI_SVO_ITEMS_PER_INVOCATION;
  levels[level].dispatch = uvec4((levels[level].range.y + perGroup - 1u) / perGroup, 1u, 1u, 0u);
  if (level == depth) {
    // The leaf level: the list of occupied leaves is complete (the level above appended them).
    uint count = min(counters.groups.w, (uint(leafList.length()) - DYNGI_SVO_LEAF_LIST_HEADER) / DYNGI_SVO_LEAF_ENTRY_UINTS);
    leafList[0] = (count + perGroup - 1u) / perGroup;
    leafList[1] = 1u;
    leafList[2] = 1u;
    leafList[3] = count;
  }
}
