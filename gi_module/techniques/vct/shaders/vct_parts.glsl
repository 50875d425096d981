// A radiance update spread over frames (--radiance-frames, a GI budget's radiance_update_fraction): part p
// of N is the p-th of N equal runs of the SVO's leaf list, about a N-th of the leaves. The list is close
// to Morton order (each subgroup's leaves in order, the subgroups in the order their appends land), so
// a part is mostly one region of space. A mip texel belongs to the part whose code range holds its cell's
// last leaf-level code; each level's texels of a part are found as a run of its nodes by a binary search
// on that code, and the runs of the N parts tile the level whatever its order. Every leaf and every
// texel is written once in N frames; a texel may be written before its last children are, so the volume
// is exact a cycle or two after a change (tested at three).
// A frame whose SVO build changed voxels (a moved object) also updates whatever lies in the changed
// boxes, so an object is never seen without its light.
// The includer declares `leafList` ({ uvec4 header; uvec2 entries[]; }: .w the leaf count, entries' .y
// their Morton codes) and `changedBoxes` (uvec4 pairs: min, max voxel, inclusive).
#ifndef DYNGI_VCT_PARTS_GLSL
#define DYNGI_VCT_PARTS_GLSL

// The leaf-list indices [x, y) of part `part` of `parts`.
uvec2 vctPartRange(uint part, uint parts) {
  uint n = leafList.header.w;
  return uvec2(n * part / parts, n * (part + 1u) / parts);
}

// The leaf-level Morton codes [x, y) of part `part` of `parts`: from its first leaf's code to the next
// part's (the first part from 0, the last to the end).
uvec2 vctPartCodes(uint part, uint parts) {
  uint n = leafList.header.w;
  if (parts <= 1u || n == 0u) return uvec2(0u, 0xFFFFFFFFu);
  uvec2 r = vctPartRange(part, parts);
  return uvec2(part == 0u ? 0u : leafList.entries[r.x].y, part + 1u == parts ? 0xFFFFFFFFu : leafList.entries[r.y].y);
}

// Whether the cell whose leaf-level Morton codes end at `lastCode` is updated in part `part` of `parts`.
bool vctCellInPart(uint lastCode, uint part, uint parts) {
  uvec2 codes = vctPartCodes(part, parts);
  return lastCode >= codes.x && (part + 1u >= parts || lastCode < codes.y);
}

// Whether the voxels [lo, hi] (inclusive) meet one of the first `count` changed boxes.
bool vctInChangedBox(uvec3 lo, uvec3 hi, uint count) {
  for (uint b = 0u; b < count; ++b)
    if (all(lessThanEqual(lo, changedBoxes[2u * b + 1u].xyz)) && all(greaterThanEqual(hi, changedBoxes[2u * b].xyz))) return true;
  return false;
}

// Whether leaf-list entry i lies in one of the first `count` changed boxes.
bool vctLeafInChangedBox(uint i, uint count) {
  uvec3 v = uvec3(svoCellOfMortonCode(leafList.entries[i].y));
  return vctInChangedBox(v, v, count);
}

// Grid-stride rounds (as VCT_FOR_EACH_LEAF) over the run `own` of the leaf list (vctPartRange) or, when
// `boxCount` boxes changed, over the whole list: the body skips what is neither in the run nor in a box.
// A run is at most the whole list, so the rounds cover it.
#define VCT_FOR_EACH_PART_LEAF(i, own, boxCount)                                                         \
  for (uint vctRound = 0u, vctStride = gl_NumWorkGroups.x * gl_WorkGroupSize.x,                          \
            vctEnd = (boxCount) > 0u ? leafList.header.w : (own).y,                                      \
            i = ((boxCount) > 0u ? 0u : (own).x) + gl_GlobalInvocationID.x;                              \
       vctRound < DYNGI_SVO_ITEMS_PER_INVOCATION && i < vctEnd; ++vctRound, i += vctStride)

bool vctInRun(uint i, uvec2 run) { return i >= run.x && i < run.y; }

#endif
