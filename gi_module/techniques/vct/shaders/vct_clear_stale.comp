#version 460
// The per-voxel state of the cells that emptied with the last SVO build, zeroed: set in the build
// before's occupancy pyramid, clear in the last one's. Radiance level 0, the direct radiance and the
// carried bounce light at emptied leaves, the anisotropic atlas' level-0 and level-1 texels (all six
// slabs) at emptied nodes of the two levels above; the passes after only write occupied voxels and
// texels, so what emptied would stay behind. (The atlas' coarser levels are cleared whole: the mips
// write every occupied texel.)
// Visits runs of 32 cells (consecutive Morton codes: a 4 x 4 x 2 brick) covering the boxes where
// voxels may have emptied (VoxelScene::staleBoxes; VoxelConeTracing lists the runs): a moving object's
// box holds ten times the cells it left, and zeroing whole boxes by copies ran on one thread.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
#include "svo_morton.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_RUNS) readonly buffer Runs { uvec2 runs[]; };
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_PREVIOUS_OCCUPANCY) readonly buffer Previous { uint previous[]; };
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_OCCUPANCY) readonly buffer Occupancy { uint occupancy[]; };
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_RADIANCE, rgba16f) uniform writeonly image3D radiance;
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_DIRECT, rgba16f) uniform writeonly image3D direct;
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_ATLAS, rgba16f) uniform writeonly image3D atlas;
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_ATLAS_1, rgba16f) uniform writeonly image3D atlas1;
layout(set = 0, binding = DYNGI_VCT_CLEAR_BINDING_CARRIED, rgba16f) uniform writeonly image3D carried;
layout(push_constant) uniform Push { DYNGI_VCT_CLEAR_PUSH };

// The 32 bits from bit `first` of a pyramid (levels do not start at word boundaries).
uint bitsFrom(uint first, bool ofPrevious) {
  uint word = first >> 5u, shift = first & 31u;
  uint next = min(word + 1u, uint(occupancy.length()) - 1u);  // a run ends inside its level: the last word's next is never needed
  uint lo = ofPrevious ? previous[word] : occupancy[word], hi = ofPrevious ? previous[next] : occupancy[next];
  return shift == 0u ? lo : (lo >> shift) | (hi << (32u - shift));
}

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= runs.length() || k >= runCount) return;
  uint level = runs[k].x, code = runs[k].y;
  uint first = DYNGI_SVO_LEVEL_BASE(level) + code;
  // A level of fewer than 32 cells (only below level 2) ends inside the run.
  uint cells = level >= 2u ? 32u : (1u << (3u * level)), valid = cells == 32u ? ~0u : (1u << cells) - 1u;
  uint emptied = bitsFrom(first, true) & ~bitsFrom(first, false) & valid;
  // The leaves' voxels; the nodes of the level above, the atlas' level-0 texels; of the level above that,
  // its level-1 texels (slabs half as wide).
  bool leaves = level == depth, atlas0 = level + 1u == depth;
  while (emptied != 0u) {
    uint b = findLSB(emptied);
    emptied &= emptied - 1u;
    ivec3 cell = svoCellOfMortonCode(code + b);
    if (leaves) {
      imageStore(radiance, cell, vec4(0.0));
      imageStore(direct, cell, vec4(0.0));
      imageStore(carried, cell, vec4(0.0));
    } else if (atlas0) {
      for (uint s = 0u; s < DYNGI_VCT_SLABS; ++s) imageStore(atlas, cell + ivec3(int(s * atlasSlabWidth), 0, 0), vec4(0.0));
    } else {
      for (uint s = 0u; s < DYNGI_VCT_SLABS; ++s) imageStore(atlas1, cell + ivec3(int(s * atlasSlabWidth / 2u), 0, 0), vec4(0.0));
    }
  }
}
