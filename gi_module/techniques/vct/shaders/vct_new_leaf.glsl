// Whether a leaf is new since the SVO build before: a moved object's new voxels, which a spread update
// visits at once (vct_parts.glsl). The includer declares `leafList` and `previousOccupancy` (the build
// before's occupancy pyramid, DYNGI_SVO_LEVEL_BASE-indexed bits).
#ifndef DYNGI_VCT_NEW_LEAF_GLSL
#define DYNGI_VCT_NEW_LEAF_GLSL

// Whether leaf-list entry i is a voxel the build before did not have (`res` = 2^depth voxels per side).
bool vctIsNewLeaf(uint i, float res) {
  uint bit = DYNGI_SVO_LEVEL_BASE(uint(findMSB(uint(res)))) + leafList.entries[i].y;
  return (previousOccupancy[bit >> 5u] & (1u << (bit & 31u))) == 0u;
}

#endif
