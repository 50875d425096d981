#version 460
// The voxel attributes image from the leaf sums (DYNGI_SVO_VOXEL_ATTRIBUTES in gi_gpu_types.h), one step
// a dispatch (kStep, DYNGI_VOXEL_ATTRIBUTES_STEP_*). Every leaf sum read is cleared after: the sums are
// zero again when the build ends, so the next one needs no clear of them.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kStep = DYNGI_VOXEL_ATTRIBUTES_STEP_STATIC;
layout(set = 0, binding = DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEVELS) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_SUMS) buffer Sums { uvec4 sums[]; };  // DYNGI_LEAF_ATTRIBUTE_INTS / 4 a leaf
layout(set = 0, binding = DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_VOXELS, rgba32ui) uniform uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_MOVING) buffer Moving { uvec4 header; uvec4 entries[]; } moving;
layout(push_constant) uniform Push { DYNGI_SVO_VOXEL_ATTRIBUTES_PUSH };
#define DYNGI_LEAF_SUMS
#include "leaf_attributes.glsl"
#include "svo_morton.glsl"

void clearSums(uint leaf) {
  sums[2u * leaf] = uvec4(0u);
  sums[2u * leaf + 1u] = uvec4(0u);
}

void main() {
  if (kStep == DYNGI_VOXEL_ATTRIBUTES_STEP_ARGS) {
    moving.header.xyz = uvec3((moving.header.w + 63u) / 64u, 1u, 1u);
    return;
  }
  if (kStep == DYNGI_VOXEL_ATTRIBUTES_STEP_STATIC) {
    // Grid-stride rounds over the SVO's leaf list, dispatched with its header (DYNGI_SVO_ITEMS_PER_INVOCATION
    // leaves per invocation); the image was cleared.
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint r = 0u, k = gl_GlobalInvocationID.x; r < DYNGI_SVO_ITEMS_PER_INVOCATION; ++r, k += stride) {
      if (k >= leafList.header.w) return;
      uvec2 entry = leafList.entries[k];  // node, cell
      uint leaf = entry.x - levels[depth].range.x;
      if (leaf >= leafCapacity) continue;
      LeafSums s = leafSums(leaf);
      if (s.count == 0u) continue;
      imageStore(voxelAttributes, svoCellOfMortonCode(entry.y), packSums(s));
      clearSums(leaf);
    }
    return;
  }
  // The moving leaves, one an invocation (dispatched with the list's header).
  uint k = gl_GlobalInvocationID.x;
  if (k >= moving.header.w || k >= uint(moving.entries.length()) / 2u) return;
  uvec4 entry = moving.entries[2u * k];
  ivec3 voxel = svoCellOfMortonCode(entry.y);
  if (kStep == DYNGI_VOXEL_ATTRIBUTES_STEP_RESTORE) {
    imageStore(voxelAttributes, voxel, moving.entries[2u * k + 1u]);
    return;
  }
  // DYNGI_VOXEL_ATTRIBUTES_STEP_MERGE: the static entities' means there (or nothing) with this build's sums.
  uvec4 before = imageLoad(voxelAttributes, voxel);
  moving.entries[2u * k + 1u] = before;
  imageStore(voxelAttributes, voxel, packSums(addSums(unpackSums(before), leafSums(entry.x))));
  clearSums(entry.x);
}
