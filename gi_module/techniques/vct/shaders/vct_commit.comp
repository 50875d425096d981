#version 460
// Copies each occupied voxel's bounced radiance (vct_bounce.comp's OUT) into level 0 of the radiance
// volume; empty voxels there are already clear.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_DIRECT, rgba16f) uniform readonly image3D bounced;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_OUT, rgba16f) uniform writeonly image3D radiance;
layout(push_constant) uniform Push { DYNGI_VCT_BOUNCE_PUSH };
#include "vct_leaves.glsl"

void main() {
  VCT_FOR_EACH_LEAF(i) {
    VctLeaf leaf;
    if (vctLeaf(i, leaf)) imageStore(radiance, leaf.voxel, imageLoad(bounced, leaf.voxel));
  }
}
