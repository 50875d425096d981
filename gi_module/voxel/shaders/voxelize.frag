#version 460
// One fragment = one pixel column along the dominant axis. Tests the (at most three) voxels of the
// column that the triangle's plane can reach inside this pixel exactly, and appends a fragment record
// (coord, albedo, normal, emission) for each voxel the triangle overlaps into this entity's range.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
#include "shared/normal_map.h"
#include "tri_box.glsl"

layout(push_constant) uniform Push { VoxelizePush pc; };
// Material variants (VoxelScene::voxelizePipelineFor): texture lookups compiled in only when used.
layout(constant_id = 0) const bool kBaseColorTexture = true;
layout(constant_id = 1) const bool kEmissiveTexture = true;
layout(constant_id = 2) const bool kMetallicRoughnessTexture = true;
layout(constant_id = 3) const bool kAlphaMask = false;  // alphaMode MASK: voxels where the texture's alpha is cut stay empty
layout(constant_id = 4) const bool kNormalTexture = false;  // with voxelize_tangent.vert
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_FRAGMENTS) buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_COUNTERS) buffer Counters { uint counters[]; };
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX) uniform sampler2D baseColorTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX) uniform sampler2D emissiveTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_METALLIC_ROUGHNESS_TEX) uniform sampler2D metallicRoughnessTex;
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_NORMAL_TEX) uniform sampler2D normalTex;

layout(location = 0) flat in vec3 v0;
layout(location = 1) flat in vec3 v1;
layout(location = 2) flat in vec3 v2;
layout(location = 3) flat in vec2 uv0;
layout(location = 4) flat in vec2 uv1;
layout(location = 5) flat in vec2 uv2;
layout(location = 6) flat in uint axis;
layout(location = 7) flat in vec3 n0;  // with a normal texture: the vertices' normals and tangents
layout(location = 8) flat in vec3 n1;
layout(location = 9) flat in vec3 n2;
layout(location = 10) flat in vec4 t0;
layout(location = 11) flat in vec4 t1;
layout(location = 12) flat in vec4 t2;
layout(location = 13) flat in vec4 instAlbedo;    // rgb base colour factor, a metallic factor
layout(location = 14) flat in vec4 instEmission;  // rgb emitted radiance, a the alpha mask's threshold
layout(location = 15) flat in uvec4 instRange;    // first slot, capacity, counter of the entity's range; w the normal scale's bits

const float kEps = 1e-4;  // voxel units: touching counts as overlapping, so nothing is missed

vec3 unproject(vec2 uv, float w, uint a) {
  return a == 0u ? vec3(w, uv.x, uv.y) : (a == 1u ? vec3(uv.y, w, uv.x) : vec3(uv.x, uv.y, w));
}
float depthOf(vec3 p, uint a) { return a == 0u ? p.x : (a == 1u ? p.y : p.z); }

uint packEmission(vec3 e) {
  float m = max(e.r, max(e.g, e.b));
  if (m <= 0.0) return 0u;
  int k = clamp(int(ceil(log2(m))), -8, 23);
  vec3 s = clamp(e / exp2(float(k)), 0.0, 1.0);
  return packUnorm4x8(vec4(s, float(k + 8) / 255.0));
}

void main() {
  int res = int(pc.resolution);
  ivec2 px = ivec2(floor(gl_FragCoord.xy));
  vec3 n = cross(v1 - v0, v2 - v0);
  float nw = depthOf(n, axis);
  // Depth range of the plane over the pixel square (|slope| <= 1 for the dominant axis), clamped to the
  // triangle's own depth range.
  float dMin = 1e30, dMax = -1e30;
  for (int i = 0; i < 4; ++i) {
    vec2 q = vec2(px) + vec2(i & 1, i >> 1);
    vec3 onAxis = unproject(q, 0.0, axis);
    float w = (dot(n, v0) - dot(n, onAxis)) / nw;
    dMin = min(dMin, w);
    dMax = max(dMax, w);
  }
  float tMin = min(depthOf(v0, axis), min(depthOf(v1, axis), depthOf(v2, axis)));
  float tMax = max(depthOf(v0, axis), max(depthOf(v1, axis), depthOf(v2, axis)));
  int z0 = max(int(floor(max(dMin, tMin) - kEps)), 0);
  int z1 = min(int(floor(min(dMax, tMax) + kEps)), res - 1);
  if (px.x < 0 || px.y < 0 || px.x >= res || px.y >= res) return;

  vec3 nrm = normalize(n);
  vec3 emission = instEmission.rgb;
  for (int z = z0; z <= z1; ++z) {
    ivec3 v = ivec3(unproject(vec2(px), float(z), axis));
    vec3 center = vec3(v) + 0.5;
    if (!triangleOverlapsBox(center, vec3(0.5 + kEps), v0, v1, v2)) continue;
    vec4 albedo = vec4(instAlbedo.rgb, 1.0);
    float metallic = instAlbedo.a;
    emission = instEmission.rgb;
    float alpha = 1.0;
    vec3 normal = nrm;
    if (kBaseColorTexture || kEmissiveTexture || kMetallicRoughnessTexture || kNormalTexture) {
      // Barycentrics of the voxel centre's projection onto the triangle (clamped) for texturing.
      vec3 p = center - dot(center - v0, nrm) * nrm;
      vec3 e0 = v1 - v0, e1 = v2 - v0, ep = p - v0;
      float d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1), d20 = dot(ep, e0), d21 = dot(ep, e1);
      float den = d00 * d11 - d01 * d01;
      float bv = den != 0.0 ? (d11 * d20 - d01 * d21) / den : 0.0;
      float bw = den != 0.0 ? (d00 * d21 - d01 * d20) / den : 0.0;
      vec3 bary = clamp(vec3(1.0 - bv - bw, bv, bw), 0.0, 1.0);
      bary /= max(bary.x + bary.y + bary.z, 1e-6);
      vec2 uv = bary.x * uv0 + bary.y * uv1 + bary.z * uv2;
      if (kBaseColorTexture) {
        vec4 texel = textureLod(baseColorTex, uv, 0.0);
        albedo.rgb *= texel.rgb;
        alpha = texel.a;
      }
      if (kEmissiveTexture) emission *= textureLod(emissiveTex, uv, 0.0).rgb;
      if (kMetallicRoughnessTexture) metallic *= textureLod(metallicRoughnessTex, uv, 0.0).b;
      if (kNormalTexture) {
        // The shading normal at the voxel centre's projection, kept on the face normal's side (the side
        // the fragments' normals are averaged on); the voxel's normal is then the mean of its fragments'.
        vec3 ns = normalize(bary.x * n0 + bary.y * n1 + bary.z * n2);
        vec4 tangent = vec4(bary.x * t0.xyz + bary.y * t1.xyz + bary.z * t2.xyz, t0.w);
        normal = perturbNormal(ns, tangent, textureLod(normalTex, uv, 0.0).rgb, uintBitsToFloat(instRange.w));
        if (dot(ns, nrm) < 0.0) normal = -normal;
      }
    }
    if (kAlphaMask && alpha < instEmission.a) continue;  // cut out at the voxel's centre
    albedo.rgb *= 1.0 - metallic;  // the diffuse share
    uint slot = atomicAdd(counters[instRange.z], 1u);
    if (slot >= instRange.y) continue;  // over capacity: counted, so the host grows the range
    uint coord = uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
    fragments[instRange.x + slot] = uvec4(coord, packUnorm4x8(albedo), packSnorm4x8(vec4(normal, 0.0)), packEmission(emission));
  }
}
