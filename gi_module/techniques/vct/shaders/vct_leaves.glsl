// The occupied voxels (the SVO's leaves) as the VCT passes over them see them: a leaf's voxel from its
// cell's Morton code, its averaged attributes (DYNGI_LEAF_* in gi_gpu_types.h). The includer declares
// `leafList` (the SVO's compacted occupied leaves), `nodeCells`, `levels`, `attributes` and the push
// members `depth`, `leafCapacity`.
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

// Entry k of the leaf list (0 .. its count); false past the count (or for a leaf without fragments).
bool vctLeaf(uint k, out VctLeaf leaf) {
  if (k >= leafList[3]) return false;
  uint node = leafList[DYNGI_SVO_LEAF_LIST_HEADER + k];
  uint i = node - levels[depth].range.x;  // its slot in the leaf level: the attributes' index
  if (i >= leafCapacity) return false;
  LeafAttributes a = leafAttributes(i);
  if (a.count == 0u) return false;
  leaf.voxel = vctCellOf(nodeCells[node]);
  leaf.albedo = a.albedo;
  leaf.normalSum = a.normalSum;
  leaf.emission = a.emission;
  return true;
}

// Grid-stride rounds over the leaf list, dispatched with its indirect arguments (its header:
// DYNGI_SVO_ITEMS_PER_INVOCATION leaves per invocation).
#define VCT_FOR_EACH_LEAF(i)                                                          \
  for (uint vctRound = 0u, vctStride = gl_NumWorkGroups.x * gl_WorkGroupSize.x, i = gl_GlobalInvocationID.x; \
       vctRound < DYNGI_SVO_ITEMS_PER_INVOCATION; ++vctRound, i += vctStride)

#endif
