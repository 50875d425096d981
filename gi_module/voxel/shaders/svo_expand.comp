#version 460
// SVO build, step 2 of a level: every occupied node of `level` gets a group of 8 children, flagged from
// one byte of the occupancy pyramid at level + 1 (DYNGI_SVO_LEVEL_BASE), the group its first child's
// Morton code (its siblings' follow from it: SVO_NODE_CELL in svo_morton.glsl). One invocation writes a
// whole group, so no atomics touch the nodes; the groups come from one counter (an append per subgroup
// for all its invocations' nodes).
// Nodes are visited in level order, which keeps a level's groups contiguous (svo_level.comp relies on it).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "voxel_shared.h"
#extension GL_KHR_shader_subgroup_ballot : require
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

// One subgroup-wide append for a run of counts (`count` per invocation): each invocation gets the first of
// its `count` consecutive indices from `counter`, in lane order. One atomic per subgroup.
#define DYNGI_SUBGROUP_APPEND_COUNT(counter, count, index)                  \
  {                                                                       \
    uint total_ = subgroupAdd(count), base_ = 0u;                         \
    if (total_ > 0u && subgroupElect()) base_ = atomicAdd(counter, total_); \
    index = subgroupBroadcastFirst(base_) + subgroupExclusiveAdd(count);  \
  }

// An invocation's nodes: DYNGI_SVO_ITEMS_PER_INVOCATION consecutive ones of the level (its `run`), so
// that one append per subgroup serves all of them (an append per node and round put two atomics a round
// on the two counters every lane of both threads hits: what this pass cost most), and consecutive nodes
// still get consecutive groups (the leaves stay in Morton order, which the passes over them read).
void main() {
  uint n = levels[level].range.y, first = levels[level].range.x;
  uint run = gl_GlobalInvocationID.x * DYNGI_SVO_ITEMS_PER_INVOCATION;
  bool childrenAreLeaves = level + 1u == depth;
  // 1. Which nodes of the run are occupied and not yet subdivided, and (above the leaves) their leaves.
  uint wantMask = 0u, wants = 0u, leaves = 0u;
  for (uint r = 0u; r < DYNGI_SVO_ITEMS_PER_INVOCATION; ++r) {
    uint i = run + r;
    if (i >= n || nodes[first + i] != DYNGI_SVO_FLAG) continue;
    wantMask |= 1u << r;
    ++wants;
    if (childrenAreLeaves) leaves += bitCount(childOccupancy(level, SVO_NODE_CELL(nodeCells, first + i)));
  }
  // 2. Their groups and leaf-list entries, one append each (uniform control flow: every lane is here).
  uint g, leafBase;
  DYNGI_SUBGROUP_APPEND_COUNT(counters.groups.x, wants, g)
  DYNGI_SUBGROUP_APPEND_COUNT(counters.groups.w, leaves, leafBase)
  uint entry = DYNGI_SVO_LEAF_LIST_HEADER + DYNGI_SVO_LEAF_ENTRY_UINTS * leafBase;
  // 3. Each wanted node gets a group of 8 children, flagged from one byte of the pyramid at level + 1.
  for (uint r = 0u; r < DYNGI_SVO_ITEMS_PER_INVOCATION; ++r) {
    if (((wantMask >> r) & 1u) == 0u) continue;
    uint node = first + run + r;
    uint code = SVO_NODE_CELL(nodeCells, node), children = childOccupancy(level, code);
    if (g >= counters.groups.y) {
      counters.groups.z = 1u;  // overflow: the node stays flagged without children (treated as occupied)
      // Its leaves were counted: their entries name no node and a cell outside any volume (the passes
      // over leaves read no attributes there and skip them).
      for (uint c = 0u; c < 8u && childrenAreLeaves && writeLeafList != 0u; ++c)
        if (((children >> c) & 1u) != 0u && entry + 1u < uint(leafList.length())) {
          leafList[entry++] = 0xFFFFFFFFu;
          leafList[entry++] = 0x3FFFFFFFu;
        }
      continue;
    }
    for (uint c = 0u; c < 8u; ++c) nodes[8u * g + c] = ((children >> c) & 1u) != 0u ? DYNGI_SVO_FLAG : 0u;
    nodeCells[8u * g] = 8u * code;  // the group's first cell: its siblings' follow (SVO_NODE_CELL)
    nodes[node] = DYNGI_SVO_FLAG | g;
    // The leaves into the list (the leaf counter counts them either way).
    for (uint c = 0u; c < 8u && childrenAreLeaves && writeLeafList != 0u; ++c)
      if (((children >> c) & 1u) != 0u && entry + 1u < uint(leafList.length())) {
        leafList[entry++] = 8u * g + c;
        leafList[entry++] = 8u * code + c;
      }
    ++g;
  }
}
