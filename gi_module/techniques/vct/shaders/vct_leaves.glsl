// The occupied voxels (the SVO's leaves) as the VCT passes over them see them: a leaf's voxel from its
// cell's Morton code, its averaged attributes (DYNGI_LEAF_* in gi_gpu_types.h). The includer declares
// `nodes`, `nodeCells`, `levels`, `attributes` and the push members `depth`, `leafCapacity`.
#ifndef DYNGI_VCT_LEAVES_GLSL
#define DYNGI_VCT_LEAVES_GLSL

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
  uint base = i * DYNGI_LEAF_ATTRIBUTE_INTS;
  float count = float(attributes[base + DYNGI_LEAF_COUNT]);
  if (count <= 0.0) return false;
  uint a = base + DYNGI_LEAF_ALBEDO, n = base + DYNGI_LEAF_NORMAL, e = base + DYNGI_LEAF_EMISSION;
  leaf.voxel = vctCellOf(nodeCells[node]);
  leaf.albedo = vec3(attributes[a], attributes[a + 1u], attributes[a + 2u]) / (255.0 * count);
  leaf.normalSum = vec3(attributes[n], attributes[n + 1u], attributes[n + 2u]) / (127.0 * count);
  float emitters = max(float(attributes[base + DYNGI_LEAF_EMITTERS]), 1.0);
  leaf.emission = vec3(attributes[e], attributes[e + 1u], attributes[e + 2u]) / (DYNGI_LEAF_EMISSION_SCALE * emitters);
  return true;
}

// Grid-stride rounds over the leaf level, dispatched with the level's indirect arguments
// (levels[depth].dispatch: DYNGI_SVO_ITEMS_PER_INVOCATION leaves per invocation).
#define VCT_FOR_EACH_LEAF(i)                                                          \
  for (uint vctRound = 0u, vctStride = gl_NumWorkGroups.x * gl_WorkGroupSize.x, i = gl_GlobalInvocationID.x; \
       vctRound < DYNGI_SVO_ITEMS_PER_INVOCATION; ++vctRound, i += vctStride)

#endif
