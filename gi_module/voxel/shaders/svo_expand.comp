#version 460
// SVO build, step 2 of a level: every occupied node of `level` gets a group of 8 children, flagged from
// one byte of the occupancy pyramid at level + 1 (DYNGI_SVO_LEVEL_BASE), the group its first child's
// Morton code (its siblings' follow from it: SVO_NODE_CELL in svo_morton.glsl). One invocation writes a
// whole group, so no atomics touch the nodes; the groups come from one counter (an append per subgroup).
// Nodes are visited in level order, which keeps a level's groups contiguous (svo_level.comp relies on it).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shared/gi_gpu_types.h"
#include "subgroup_append.glsl"
#include "svo_morton.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_NODES) buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_NODE_CELLS) buffer NodeCells { uint nodeCells[]; };
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_OCCUPANCY) readonly buffer Occupancy { uint occupancy[]; };
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_LEVELS) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_COUNTERS) buffer Counters { SvoCounters counters; };
// The occupied leaves (node index, cell) after DYNGI_SVO_LEAF_LIST_HEADER uints (gi_gpu_types.h): appended by
// the expand of the level above the leaves, as many as the leaf counter counts.
layout(set = 0, binding = DYNGI_SVO_EXPAND_BINDING_LEAF_LIST) writeonly buffer LeafList { uint leafList[]; };
layout(push_constant) uniform Push { DYNGI_SVO_EXPAND_PUSH };

// The occupancy of the 8 children of the cell with Morton code m at level l (bit c: child c).
uint childOccupancy(uint l, uint m) {
  uint index = DYNGI_SVO_LEVEL_BASE(l + 1u) + 8u * m;  // a multiple of 8: one byte of one word
  return (occupancy[index >> 5] >> (index & 31u)) & 255u;
}

void expand(uint node) {
  bool want = nodes[node] == DYNGI_SVO_FLAG;  // occupied, not yet subdivided
  uint g;
  DYNGI_SUBGROUP_APPEND(counters.groups.x, want, g)
  uint leaves = 0u, children = 0u, code = 0u;
  if (want && g >= counters.groups.y) {
    counters.groups.z = 1u;  // overflow: the node stays flagged without children (treated as occupied)
  } else if (want) {
    code = SVO_NODE_CELL(nodeCells, node);
    children = childOccupancy(level, code);
    bool childrenAreLeaves = level + 1u == depth;
    for (uint c = 0u; c < 8u; ++c) {
      bool o = ((children >> c) & 1u) != 0u;
      nodes[8u * g + c] = o ? DYNGI_SVO_FLAG : 0u;
    }
    nodeCells[8u * g] = 8u * code;  // the group's first cell: its siblings' follow (SVO_NODE_CELL)
    if (childrenAreLeaves) leaves = bitCount(children);
    nodes[node] = DYNGI_SVO_FLAG | g;
  }
  // The leaves into the list, one atomic per subgroup (as DYNGI_SUBGROUP_APPEND, for counts).
  uint subgroupLeaves = subgroupAdd(leaves), first = subgroupExclusiveAdd(leaves), base = 0u;
  if (subgroupLeaves > 0u && subgroupElect()) base = atomicAdd(counters.groups.w, subgroupLeaves);
  base = DYNGI_SVO_LEAF_LIST_HEADER + DYNGI_SVO_LEAF_ENTRY_UINTS * (subgroupBroadcastFirst(base) + first);
  for (uint c = 0u; c < 8u && leaves > 0u && writeLeafList != 0u; ++c)
    if (((children >> c) & 1u) != 0u && base + 1u < uint(leafList.length())) {
      leafList[base++] = 8u * g + c;
      leafList[base++] = 8u * code + c;
    }
}

void main() {
  uint n = levels[level].range.y, stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  // Uniform trip count per subgroup: the subgroup operations inside need every invocation.
  uint rounds = (n + stride - 1u) / stride;
  for (uint r = 0u; r < rounds; ++r) {
    uint i = gl_GlobalInvocationID.x + r * stride;
    if (i < n) expand(levels[level].range.x + i);
  }
}
