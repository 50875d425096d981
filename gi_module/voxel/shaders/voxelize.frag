#version 460
// One fragment = one pixel column along the dominant axis. Tests the (at most three) voxels of the
// column that the triangle's plane can reach inside this pixel exactly, and appends a fragment record
// (coord, albedo, normal, emission) for each voxel the triangle overlaps into this entity's range.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
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
#include "voxel_fragment.glsl"

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

const float kEps = kVoxelTouchEps;

vec3 unproject(vec2 uv, float w, uint a) {
  return a == 0u ? vec3(w, uv.x, uv.y) : (a == 1u ? vec3(uv.y, w, uv.x) : vec3(uv.x, uv.y, w));
}
float depthOf(vec3 p, uint a) { return a == 0u ? p.x : (a == 1u ? p.y : p.z); }

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
  VoxelTriangle t = VoxelTriangle(v0, v1, v2, uv0, uv1, uv2, n0, n1, n2, t0, t1, t2, instAlbedo, instEmission, instRange);
  for (int z = z0; z <= z1; ++z) {
    ivec3 v = ivec3(unproject(vec2(px), float(z), axis));
    if (triangleOverlapsBox(vec3(v) + 0.5, vec3(0.5 + kEps), v0, v1, v2)) appendVoxelFragment(v, t, nrm);
  }
}
