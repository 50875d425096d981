#version 460
// One more light bounce: per occupied voxel, the light arriving through `cones` diffuse cones around its
// normal over the radiance volume as it stands (direct light, or the bounce before), reflected by its
// albedo and added to its own direct radiance: OUT = DIRECT + albedo E / pi. vct_commit.comp then copies
// OUT into level 0 of the radiance volume (a pass apart: the cones read that level while this one runs).
// kCarried: the voxels' carried bounce light instead (VctOptions::bounceFrames), OUT = albedo E / pi over
// this frame's part of them and the voxels the SVO build added; the radiance it reads holds what they
// carried before, so the light gains a bounce each time a voxel's turn comes round.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
layout(local_size_x = 64) in;
layout(constant_id = 0) const bool kAnisotropic = false;
layout(constant_id = 1) const bool kCarried = false;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_DIRECT, rgba16f) uniform readonly image3D direct;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_RADIANCE) uniform sampler3D vctRadiance;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_ANISO) uniform sampler3D vctAniso;
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_OUT, rgba16f) uniform writeonly image3D outRadiance;
layout(push_constant) uniform Push { DYNGI_VCT_BOUNCE_PUSH };
#include "vct_cone.glsl"
#include "vct_leaves.glsl"
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_CHANGED_BOXES) readonly buffer ChangedBoxes { uvec4 changedBoxes[]; };
layout(set = 0, binding = DYNGI_VCT_BOUNCE_BINDING_PREVIOUS_OCCUPANCY) readonly buffer Previous { uint previousOccupancy[]; };
#include "vct_parts.glsl"
#include "vct_new_leaf.glsl"

void bounce(uint i) {
  VctLeaf leaf;
  if (!vctLeaf(i, leaf)) return;
  float nLen = length(leaf.normalSum);
  vec3 L = kCarried ? vec3(0.0) : imageLoad(direct, leaf.voxel).rgb;
  if (nLen > 0.3) {  // a voxel whose fragments face both ways keeps its direct light only
    float ao;
    // From the voxel's centre: its surface is within half a voxel of it.
    vec3 e = vctDiffuse(vec3(leaf.voxel) + 0.5, leaf.normalSum / nLen, 0.0, 0u, 1u, ao);
    L += leaf.albedo * e;
  }
  imageStore(outRadiance, leaf.voxel, vec4(L, 1.0));
}

void main() {
  if (!kCarried) {
    VCT_FOR_EACH_LEAF(i) bounce(i);
    return;
  }
  // This frame's run of the leaves and, with changed boxes, the leaves in them that the build before did
  // not have: a moved object's new voxels. (The others keep their carried light until their turn.)
  uvec2 own = vctPartRange(part, parts);
  VCT_FOR_EACH_PART_LEAF(i, own, boxCount) {
    if (vctInRun(i, own) || (vctLeafInChangedBox(i, boxCount) && vctIsNewLeaf(i, res))) bounce(i);
  }
}
