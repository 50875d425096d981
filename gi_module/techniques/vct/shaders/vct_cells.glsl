// A cell of the SVO from its Morton code at its level (svo_expand.comp writes them to nodeCells).
#ifndef DYNGI_VCT_CELLS_GLSL
#define DYNGI_VCT_CELLS_GLSL

uint vctCompactBits(uint v) {  // bit 3i of v to bit i (the inverse of svoSpreadBits)
  v &= 0x09249249u;
  v = (v | (v >> 2)) & 0x030C30C3u;
  v = (v | (v >> 4)) & 0x0300F00Fu;
  v = (v | (v >> 8)) & 0x030000FFu;
  v = (v | (v >> 16)) & 0x000003FFu;
  return v;
}
ivec3 vctCellOf(uint code) { return ivec3(vctCompactBits(code), vctCompactBits(code >> 1), vctCompactBits(code >> 2)); }

#endif
