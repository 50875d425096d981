// Morton code of a cell (10 bits per axis): its bits interleaved z y x from the top, so that a cell's
// code at a coarser level is the code shifted right by 3 per level and a node's children are 8m + c
// with c = x | y << 1 | z << 2, the SVO's child order (see DYNGI_SVO_LEVEL_BASE).
uint svoSpreadBits(uint v) {  // bit i of v (i < 10) to bit 3i
  v &= 1023u;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}
uint svoMortonCode(uvec3 cell) { return svoSpreadBits(cell.x) | (svoSpreadBits(cell.y) << 1) | (svoSpreadBits(cell.z) << 2); }
