// Morton code of a cell (10 bits per axis): its bits interleaved z y x from the top, so that a cell's
// code at a coarser level is the code shifted right by 3 per level and a node's children are 8m + c
// with c = x | y << 1 | z << 2, the SVO's child order (see DYNGI_SVO_LEVEL_BASE). svo_expand.comp
// writes the node cells once per group of 8 siblings (SVO_NODE_CELL below); svoCellOfMortonCode reads a
// cell back from a code.
#ifndef DYNGI_SVO_MORTON_GLSL
#define DYNGI_SVO_MORTON_GLSL
uint svoSpreadBits(uint v) {  // bit i of v (i < 10) to bit 3i
  v &= 1023u;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}
uint svoMortonCode(uvec3 cell) { return svoSpreadBits(cell.x) | (svoSpreadBits(cell.y) << 1) | (svoSpreadBits(cell.z) << 2); }

uint svoCompactBits(uint v) {  // bit 3i of v to bit i (the inverse of svoSpreadBits)
  v &= 0x09249249u;
  v = (v | (v >> 2)) & 0x030C30C3u;
  v = (v | (v >> 4)) & 0x0300F00Fu;
  v = (v | (v >> 8)) & 0x030000FFu;
  v = (v | (v >> 16)) & 0x000003FFu;
  return v;
}
ivec3 svoCellOfMortonCode(uint code) { return ivec3(svoCompactBits(code), svoCompactBits(code >> 1), svoCompactBits(code >> 2)); }

// The Morton code of node `node`'s cell from the node cells (`cells`, a uint array). Only a group's first
// slot is written (8 times the parent's code, which is its first child's code): sibling c of a group is
// that plus c, and the root (node 0) is cell 0: one store per group instead of eight.
#define SVO_NODE_CELL(cells, node) ((cells)[(node) & ~7u] + ((node) & 7u))
#endif
