#version 460
// The light emissive surfaces send each occupied voxel, reflected: albedo E / pi, with E estimated from
// `samples` of the points sampled on the emitters by power (an evenly spaced subset, offset per voxel)
// and each point's visibility marched through the SVO. Written to the carried image, which injection
// adds to the voxel's radiance, so the voxels an emitter lights pass its light on through the cones as
// the voxels a light lights do; the cones alone would see only the emitters. Over this frame's part of
// the leaves and the voxels the SVO build added.
#extension GL_GOOGLE_include_directive : require
#include "vct_shared.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_OUT, rgba16f) uniform writeonly image3D outLight;
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_CHANGED_BOXES) readonly buffer ChangedBoxes { uvec4 changedBoxes[]; };
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_PREVIOUS_OCCUPANCY) readonly buffer Previous { uint previousOccupancy[]; };
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_SVO_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_VCT_EMITTER_BINDING_POINTS) readonly buffer Points { VctEmitterPoint points[]; };
layout(push_constant) uniform Push { DYNGI_VCT_EMITTER_PUSH };
#include "vct_leaves.glsl"
#include "vct_parts.glsl"
#include "vct_new_leaf.glsl"
#include "svo_traverse.glsl"

const float PI = 3.14159265358979;

uint hashVoxel(ivec3 v) {
  uint h = uint(v.x) * 73856093u ^ uint(v.y) * 19349663u ^ uint(v.z) * 83492791u;
  h ^= h >> 16u;
  h *= 0x7feb352du;
  return h ^ (h >> 15u);
}

void light(uint i) {
  VctLeaf leaf;
  if (!vctLeaf(i, leaf)) return;
  float voxelSize = volume.w;
  vec3 centre = volume.xyz + (vec3(leaf.voxel) + 0.5) * voxelSize;
  float nLen = length(leaf.normalSum);
  bool twoSided = nLen < 0.3;  // a wall thinner than a voxel: lit from whichever side faces the point
  vec3 n = nLen > 1e-4 ? leaf.normalSum / nLen : vec3(0.0, 1.0, 0.0);
  uint stride = uint(DYNGI_VCT_EMITTER_POINTS) / samples;
  uint first = hashVoxel(leaf.voxel) % stride;
  vec3 e = vec3(0.0);
  for (uint k = 0u; k < samples; ++k) {
    VctEmitterPoint p = points[first + k * stride];
    vec3 d = p.position.xyz - centre;
    float d2 = max(dot(d, d), 1e-12);
    vec3 w = d * inversesqrt(d2);
    vec3 nl = twoSided && dot(n, w) < 0.0 ? -n : n;
    float cr = dot(nl, w), ce = abs(dot(p.normal.xyz, w)), pdf = p.position.w;
    if (pdf > 0.0 && cr > 0.0 && ce > 0.0) {
      // No estimate above pi Le (a sky of the point's radiance): the points near a voxel next to an
      // emitter would otherwise spike by 1 / d^2.
      float g = min(cr * ce / d2, PI * pdf);
      // From one voxel out along the normal to one voxel off the emitter on the voxel's side: neither
      // the voxel's own surface nor the emitter's voxels hide the point.
      vec3 a = vec3(leaf.voxel) + 0.5 + nl;
      vec3 b = (p.position.xyz - volume.xyz) / voxelSize - p.normal.xyz * sign(dot(p.normal.xyz, w));
      uint steps;
      if (!svoOccluded(a, b, 1e-3, svoDepth, res, steps)) e += p.radiance.rgb * (g / pdf);
    }
  }
  imageStore(outLight, leaf.voxel, vec4(leaf.albedo * e / (float(samples) * PI), 1.0));
}

void main() {
  uvec2 own = vctPartRange(part, parts);
  VCT_FOR_EACH_PART_LEAF(i, own, boxCount) {
    if (vctInRun(i, own) || (vctLeafInChangedBox(i, boxCount) && vctIsNewLeaf(i, res))) light(i);
  }
}
