// The occupied voxels (the SVO's leaves) as the VCT passes over them see them: a leaf's voxel from its
// cell's Morton code, its averaged attributes from the voxel attributes image (leaf_attributes.glsl). The
// includer declares `leafList` (the SVO's compacted occupied leaves: `{ uvec4 header; uvec2 entries[]; }
// leafList`) and `voxelAttributes`.
#ifndef DYNGI_VCT_LEAVES_GLSL
#define DYNGI_VCT_LEAVES_GLSL

#include "leaf_attributes.glsl"
#include "svo_morton.glsl"

struct VctLeaf {
  ivec3 voxel;
  vec3 albedo;
  vec3 normalSum;  // mean of the fragments' unit normals: short where they disagree (both sides of a thin wall)
  vec3 emission;
};

// Entry k of the leaf list (0 .. its count); false past the count (or for a leaf without fragments).
bool vctLeaf(uint k, out VctLeaf leaf) {
  if (k >= leafList.header.w) return false;
  leaf.voxel = svoCellOfMortonCode(leafList.entries[k].y);
  // An overflowing build's entries for leaves it could not make lie outside the volume (svo_expand.comp).
  if (any(greaterThanEqual(leaf.voxel, imageSize(voxelAttributes)))) return false;
  LeafAttributes a = voxelAttributesAt(leaf.voxel);
  if (a.count == 0u) return false;
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
