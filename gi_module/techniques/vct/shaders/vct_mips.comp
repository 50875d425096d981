#version 460
// One level of the radiance volume's mip chain from the level below (premultiplied radiance, opacity).
// Isotropic: the mean of the 8 children. Anisotropic (kAnisotropic): the destination is an atlas of six
// slabs side by side along x, one per direction a cone may travel (+x, -x, +y, -y, +z, -z); for slab d
// each of the 4 pairs of children along d's axis is composited front to back as a cone travelling along
// d meets them (front + (1 - front.a) back), and the 4 are averaged: a wall one voxel thick stays opaque
// along its normal at every level instead of fading to 1/2, 1/4, ... (Crassin et al. 2011).
// The atlas is written only at the texels of occupied SVO nodes (one invocation per node writes its
// texel in all six slabs; the rest of the atlas is cleared), half the cost of a dense pass over every
// texel. The occupied nodes of a level are found as the child groups of the level below it, one a node:
// a level's own slots include the empty siblings, which cost as much as occupied ones.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
#include "svo_morton.glsl"
#include "vct_seen.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(constant_id = 0) const bool kAnisotropic = false;
// Isotropic only: each texel's opacity is that of its most opaque axis (the children composited front to
// back along it, averaged over the 4 columns), its radiance that axis' mean composite: a wall one voxel
// thick stays opaque at every level, as in the anisotropic atlas, for one fetch per sample.
layout(constant_id = 1) const bool kOpaqueAxis = false;
// Anisotropic only: the source is the isotropic level 0 (one slab), shared by the six destination slabs:
// one invocation reads its 8 children once and writes the texel in all six.
layout(constant_id = 2) const bool kSharedSource = false;
// kSharedSource only: the source is the direct-radiance volume itself (level 0 before any bounce is
// added: the same radiance), whose alpha holds the seen code (vct_seen.glsl) instead of the opacity: one
// fetch a child instead of two.
layout(constant_id = 3) const bool kSeenInSource = false;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_SOURCE, rgba16f) uniform readonly image3D source;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_DEST, rgba16f) uniform writeonly image3D dest;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_SEEN, rgba16f) uniform readonly image3D seen;  // kSharedSource: the direct radiance, for its alpha
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_NODE_CELLS) readonly buffer NodeCells { uint nodeCells[]; };
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_LEVELS) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_CHANGED_BOXES) readonly buffer ChangedBoxes { uvec4 changedBoxes[]; };
layout(push_constant) uniform Push { DYNGI_VCT_MIPS_PUSH };
#include "vct_parts.glsl"

// The last leaf-level Morton code within cell `code` of this level.
uint lastLeafCode(uint code) { return ((code + 1u) << leafShift) - 1u; }
// Whether this frame's update writes the texel of cell `code` at this level: always when not spread;
// else when this frame's part holds it or its voxels meet a changed box.
bool inThisPart(uint code) {
  if (vctCellInPart(lastLeafCode(code), part, parts)) return true;
  uint span = 1u << (leafShift / 3u);  // voxels a side
  uvec3 lo = uvec3(svoCellOfMortonCode(code)) * span;
  return vctInChangedBox(lo, lo + span - 1u, boxCount);
}
shared uint partBegin, partEnd;
// Anisotropic: a binary search over the level's `groups` nodes (from node cell `first`) for the first
// whose cell ends at or after leaf code `code`: a part's run lies between two such searches.
uint firstNodeEndingFrom(uint first, uint groups, uint code) {
  uint lo = 0u, hi = groups;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (lastLeafCode(nodeCells[first + 8u * mid] >> 3u) < code) lo = mid + 1u;
    else hi = mid;
  }
  return lo;
}

vec4 child(uint slab, ivec3 base, ivec3 offset) {
  ivec3 c = base + offset;
  c.x += int(slab * sourceSlabWidth);
  return imageLoad(source, c);
}

vec4 over(vec4 front, vec4 back) { return front + (1.0 - front.a) * back; }

// Atlas level 0 at texel p, all six slabs, from the isotropic level 0 and which cones see each voxel.
void atlasFromLevel0(ivec3 p) {
  ivec3 b = 2 * p;
  vec4 c[8];
  // Per child and axis, 1 where a cone travelling along -axis (+axis) sees its radiance: a one-sided
  // surface shows it only to cones that meet its front, its back is black (it still blocks them). A
  // thin wall's lit side then no longer reaches, through the sampler's filtering across the wall, the
  // cones on the other side, and a box's lit top not the cones passing under its edge. Two-sided
  // voxels (a wall thinner than a voxel) and a surface parallel to the axis show it both ways.
  vec3 seenTravellingMinus[8], seenTravellingPlus[8];
  for (int i = 0; i < 8; ++i) {
    ivec3 q = b + ivec3(i & 1, (i >> 1) & 1, i >> 2);
    c[i] = imageLoad(source, q);
    float code = kSeenInSource ? c[i].a : imageLoad(seen, q).a;
    if (kSeenInSource) c[i].a = code > 0.0 ? 1.0 : 0.0;  // an occupied voxel is opaque
    vctSeenFromCode(code, seenTravellingPlus[i], seenTravellingMinus[i]);
  }
  int w = int(destSlabWidth);
  // Child i as a cone travelling along +axis (plus) or -axis sees it.
#define SEEN(i, axis, plus) vec4(c[i].rgb * ((plus) ? seenTravellingPlus[i][axis] : seenTravellingMinus[i][axis]), c[i].a)
  // Child i sits at (i & 1, i >> 1 & 1, i >> 2): the pairs along x are (0,1) (2,3) (4,5) (6,7), ...
  imageStore(dest, p, 0.25 * (over(SEEN(0, 0, true), SEEN(1, 0, true)) + over(SEEN(2, 0, true), SEEN(3, 0, true)) +
                              over(SEEN(4, 0, true), SEEN(5, 0, true)) + over(SEEN(6, 0, true), SEEN(7, 0, true))));
  imageStore(dest, p + ivec3(w, 0, 0), 0.25 * (over(SEEN(1, 0, false), SEEN(0, 0, false)) + over(SEEN(3, 0, false), SEEN(2, 0, false)) +
                                               over(SEEN(5, 0, false), SEEN(4, 0, false)) + over(SEEN(7, 0, false), SEEN(6, 0, false))));
  imageStore(dest, p + ivec3(2 * w, 0, 0), 0.25 * (over(SEEN(0, 1, true), SEEN(2, 1, true)) + over(SEEN(1, 1, true), SEEN(3, 1, true)) +
                                                   over(SEEN(4, 1, true), SEEN(6, 1, true)) + over(SEEN(5, 1, true), SEEN(7, 1, true))));
  imageStore(dest, p + ivec3(3 * w, 0, 0), 0.25 * (over(SEEN(2, 1, false), SEEN(0, 1, false)) + over(SEEN(3, 1, false), SEEN(1, 1, false)) +
                                                   over(SEEN(6, 1, false), SEEN(4, 1, false)) + over(SEEN(7, 1, false), SEEN(5, 1, false))));
  imageStore(dest, p + ivec3(4 * w, 0, 0), 0.25 * (over(SEEN(0, 2, true), SEEN(4, 2, true)) + over(SEEN(1, 2, true), SEEN(5, 2, true)) +
                                                   over(SEEN(2, 2, true), SEEN(6, 2, true)) + over(SEEN(3, 2, true), SEEN(7, 2, true))));
  imageStore(dest, p + ivec3(5 * w, 0, 0), 0.25 * (over(SEEN(4, 2, false), SEEN(0, 2, false)) + over(SEEN(5, 2, false), SEEN(1, 2, false)) +
                                                   over(SEEN(6, 2, false), SEEN(2, 2, false)) + over(SEEN(7, 2, false), SEEN(3, 2, false))));
#undef SEEN
}

// A coarser atlas level at texel p of every slab, from the level below's slabs.
void atlasFromAtlas(ivec3 p) {
  ivec3 base = 2 * p;
  for (uint slab = 0u; slab < DYNGI_VCT_SLABS; ++slab) {
    uint axis = slab / 2u;
    bool negative = (slab & 1u) != 0u;
    // The pair along `axis`: the child a cone travelling along +axis meets first has the lower coordinate.
    ivec3 along = axis == 0u ? ivec3(1, 0, 0) : (axis == 1u ? ivec3(0, 1, 0) : ivec3(0, 0, 1));
    ivec3 u = axis == 0u ? ivec3(0, 1, 0) : ivec3(1, 0, 0);
    ivec3 v = axis == 2u ? ivec3(0, 1, 0) : ivec3(0, 0, 1);
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 4; ++j) {
      ivec3 o = (j & 1) * u + (j >> 1) * v;
      vec4 lo = child(slab, base, o), hi = child(slab, base, o + along);
      sum += negative ? over(hi, lo) : over(lo, hi);
    }
    imageStore(dest, p + ivec3(int(slab * destSlabWidth), 0, 0), sum * 0.25);
  }
}

void main() {
  if (kAnisotropic) {
    // Grid-stride rounds over the child groups of level nodeLevel + 1, one for each occupied node of
    // nodeLevel (its cell: the group's first cell's parent), dispatched with that level's indirect
    // arguments (levels[nodeLevel + 1].dispatch: DYNGI_SVO_ITEMS_PER_INVOCATION slots per invocation, so
    // 8 times the groups' rounds).
    // A radiance update spread over frames takes this frame's part of them (vct_parts.glsl): a run, or
    // with changed boxes every node, those outside the part and the boxes skipped.
    uint stride = gl_NumWorkGroups.x * 64u, first = levels[nodeLevel + 1u].range.x, groups = levels[nodeLevel + 1u].range.y / 8u;
    // One invocation of the workgroup searches for the run (parts is uniform: so is the barrier).
    uint begin = 0u, end = groups;
    if (parts > 1u && boxCount == 0u) {
      if (gl_LocalInvocationIndex == 0u) {
        uvec2 codes = vctPartCodes(part, parts);
        partBegin = firstNodeEndingFrom(first, groups, codes.x);
        partEnd = part + 1u == parts ? groups : firstNodeEndingFrom(first, groups, codes.y);
      }
      barrier();
      begin = partBegin;
      end = partEnd;
    }
    uint i = begin + gl_WorkGroupID.x * 64u + gl_LocalInvocationIndex;
    for (uint r = 0u; r < DYNGI_SVO_ITEMS_PER_INVOCATION; ++r, i += stride) {
      if (i >= end) break;
      uint code = nodeCells[first + 8u * i] >> 3u;
      if (boxCount > 0u && !inThisPart(code)) continue;
      ivec3 p = svoCellOfMortonCode(code);
      if (kSharedSource) atlasFromLevel0(p);
      else atlasFromAtlas(p);
    }
    return;
  }
  ivec3 size = imageSize(dest);
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p, size)) || !inThisPart(svoMortonCode(uvec3(p)))) return;
  if (!kOpaqueAxis) {
    ivec3 base = 2 * p;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i) sum += imageLoad(source, base + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    imageStore(dest, p, sum * 0.125);
    return;
  }
  // kOpaqueAxis: each texel's opacity that of its most opaque axis.
  ivec3 base = 2 * p;
  vec4 c[8];
  for (int i = 0; i < 8; ++i) c[i] = imageLoad(source, base + ivec3(i & 1, (i >> 1) & 1, i >> 2));
  vec4 best = vec4(0.0);
  for (int axis = 0; axis < 3; ++axis) {
    int step = 1 << axis;  // the child index bit of this axis
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i) {
      if ((i & step) != 0) continue;
      vec4 lo = c[i], hi = c[i | step];
      sum += 0.5 * (over(lo, hi) + over(hi, lo));  // both directions along the axis: the same opacity
    }
    sum *= 0.25;
    if (sum.a > best.a) best = sum;
  }
  imageStore(dest, p, best);
}
