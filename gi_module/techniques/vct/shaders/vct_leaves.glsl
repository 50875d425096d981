// The occupied voxels (the SVO's leaves) as the VCT passes over them see them: a leaf's voxel from its
// cell's Morton code, its averaged attributes (DYNGI_LEAF_* in gi_gpu_types.h). The includer declares
// `nodes`, `nodeCells`, `levels`, `attributes` and the push members `depth`, `leafCapacity`.
#ifndef DYNGI_VCT_LEAVES_GLSL
#define DYNGI_VCT_LEAVES_GLSL

#include "leaf_attributes.glsl"
#include "vct_cells.glsl"

struct VctLeaf {
  ivec3 voxel;
  vec3 albedo;
  vec3 normalSum;  // mean of the fragments' unit normals: short where they disagree (both sides of a thin wall)
  vec3 emission;
};

// Leaf i of the leaf level (0 .. its node count); false when that slot is empty.
bool vctLeaf(uint i, out VctLeaf leaf) {
  uint node = levels[depth].range.x + i;
  if (i >= levels[depth].range.y || nodes[node] == 0u || i >= leafCapacity) return false;
  LeafAttributes a = leafAttributes(i);
  if (a.count == 0u) return false;
  leaf.voxel = vctCellOf(nodeCells[node]);
  leaf.albedo = a.albedo;
  leaf.normalSum = a.normalSum;
  leaf.emission = a.emission;
  return true;
}

// Grid-stride rounds over the leaf level, dispatched with the level's indirect arguments
// (levels[depth].dispatch: DYNGI_SVO_ITEMS_PER_INVOCATION leaves per invocation).
#define VCT_FOR_EACH_LEAF(i)                                                          \
  for (uint vctRound = 0u, vctStride = gl_NumWorkGroups.x * gl_WorkGroupSize.x, i = gl_GlobalInvocationID.x; \
       vctRound < DYNGI_SVO_ITEMS_PER_INVOCATION; ++vctRound, i += vctStride)

#endif
