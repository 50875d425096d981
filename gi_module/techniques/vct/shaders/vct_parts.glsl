// A radiance update spread over frames (a GI budget's radiance_update_fraction): part p of N is the
// p-th of N equal runs of the SVO's leaf list, which is in Morton order, so each part is a region of
// space and every coarser cell lies within one part or spans consecutive ones. A cell belongs to the
// part of its last leaf-level code: the mips update it in the frame that updates its last children, so
// N frames after a change every leaf is new and 2N after it every texel (a cycle may start mid-way).
// The includer declares `leafList` ({ uvec4 header; uvec2 entries[]; }: .w the leaf count, entries' .y
// their Morton codes).
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

#endif
