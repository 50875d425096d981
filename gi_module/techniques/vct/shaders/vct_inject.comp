#version 460
// Radiance injection: per occupied voxel, the direct light it reflects (every light, shadowed through
// the renderer's shadow maps at the voxel's surface) plus its emission, as isotropic radiance with
// opacity 1. Blended per voxel with the previous frame's radiance (temporalBlend), except where it
// changed by more than temporalResponse (relative), so a light switched off leaves no trail. Written to
// DIRECT (the frame's history, what bounces add to; its alpha says which cones see the voxel, for the
// anisotropic atlas: vct_seen.glsl) and to level 0 of the radiance volume (opacity 1 in alpha), there with
// the light the voxel carries when it carries some (its bounce light, or its emitters' light:
// vct_emitter_light.comp).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
#include "shared/lighting.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_LEAF_LIST) readonly buffer LeafList { uvec4 header; uvec2 entries[]; } leafList;
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_SHADOW_MATRICES) readonly buffer ShadowMatrices { mat4 shadowViewProj[]; };
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_SHADOW_MAPS, r32f) uniform readonly image2DArray shadowMaps;
// Last frame's radiance at each voxel (zero where it was empty: vct_clear_stale.comp), replaced in place:
// every voxel is read and written by its own invocation alone.
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_DIRECT, rgba16f) uniform image3D direct;
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_RADIANCE, rgba16f) uniform writeonly image3D radiance;
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_CARRIED, rgba16f) uniform readonly image3D carriedLight;
layout(push_constant) uniform Push { DYNGI_VCT_INJECT_PUSH };
#include "shared/shadows.glsl"
#include "vct_leaves.glsl"
layout(set = 0, binding = DYNGI_VCT_INJECT_BINDING_CHANGED_BOXES) readonly buffer ChangedBoxes { uvec4 changedBoxes[]; };
#include "vct_parts.glsl"
#include "vct_seen.glsl"

const float PI = 3.14159265358979;

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

void inject(uint i) {
  VctLeaf leaf;
  if (!vctLeaf(i, leaf)) return;
  float voxelSize = volume.w;
  vec3 centre = volume.xyz + (vec3(leaf.voxel) + 0.5) * voxelSize;
  // The surface lies somewhere in the voxel: light it one voxel out along its normal, so neither the
  // shadow lookup nor the cosine sees the voxel's own far side. A voxel whose fragments face both ways
  // (a wall thinner than a voxel) is lit from whichever side faces the light.
  float nLen = length(leaf.normalSum);
  bool twoSided = nLen < 0.3;
  vec3 n = nLen > 1e-4 ? leaf.normalSum / nLen : vec3(0.0, 1.0, 0.0);
  vec3 irradiance = vec3(0.0);
  uint i2 = 0u;
  do {
    if (i2 < lightCount) {
      GpuLight L = lights[i2];
      if (L.radiance.w != 0.0) {
        vec3 toLight;
        float dist;
        lightIrradiance(L, centre, n, toLight, dist);  // for the direction to the light
        vec3 nl = twoSided && dot(n, toLight) < 0.0 ? -n : n;
        vec3 p = centre + nl * voxelSize;
        vec3 e = lightIrradiance(L, p, nl, toLight, dist);
        if (max(e.r, max(e.g, e.b)) > 0.0) irradiance += e * shadowFactor(L, p, nl, dist);
      }
    }
  } while (++i2 < lightCount);
  vec3 L = leaf.emission + leaf.albedo * irradiance / PI;
  if (history != 0u) {
    vec4 prev = imageLoad(direct, leaf.voxel);
    if (prev.a > 0.0) {
      float lNew = luminance(L), lOld = luminance(prev.rgb);
      float change = abs(lNew - lOld) / max(max(lNew, lOld), 1e-6);
      L = mix(L, prev.rgb, temporalBlend * clamp(1.0 - change / temporalResponse, 0.0, 1.0));
    }
  }
  imageStore(direct, leaf.voxel, vec4(L, vctSeenCode(n, twoSided)));
  if (carried != 0u) L += imageLoad(carriedLight, leaf.voxel).rgb;
  imageStore(radiance, leaf.voxel, vec4(L, 1.0));
}

void main() {
  // This frame's run of the leaves (all of them unless the update is spread over frames) and, with
  // changed boxes, the leaves in them.
  uvec2 own = vctPartRange(part, parts);
  VCT_FOR_EACH_PART_LEAF(i, own, boxCount) {
    if (vctInRun(i, own) || vctLeafInChangedBox(i, boxCount)) inject(i);
  }
}
