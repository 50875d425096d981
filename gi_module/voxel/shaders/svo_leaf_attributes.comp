#version 460
// Accumulates each fragment's albedo, normal and emission into its leaf (integer atomics; the layout is
// DYNGI_LEAF_* in gi_gpu_types.h, read through leaf_attributes.glsl). Kept in a buffer apart from the
// nodes so the visibility march never touches it.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
// False when no fragment emits (VoxelScene::fragmentsEmit): the emission sums stay 0 without the
// atomics, which lavapipe would run masked for every fragment.
layout(constant_id = 0) const bool kEmission = true;
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES) buffer Attributes { uint attributes[]; };  // DYNGI_LEAF_ATTRIBUTE_INTS per leaf
layout(push_constant) uniform Push { DYNGI_SVO_LEAF_ATTRIBUTES_PUSH };

vec3 unpackEmission(uint e) {
  vec4 v = unpackUnorm4x8(e);
  return e == 0u ? vec3(0.0) : v.rgb * exp2(round(v.a * 255.0) - 8.0);
}

void accumulate(uint i) {
  uvec4 f = fragments[i];
  if (f.x == DYNGI_VOXEL_EMPTY) return;
  // Its leaf: down from the root.
  uvec3 v = uvec3(f.x & 1023u, (f.x >> 10) & 1023u, (f.x >> 20) & 1023u);
  uint node = 0u;
  for (uint l = 0u; l < depth; ++l) {
    uint g = nodes[node] & DYNGI_SVO_GROUP_MASK;
    if (g == 0u) return;  // its branch overflowed the node pool
    uint shift = depth - 1u - l;
    node = 8u * g + (((v.x >> shift) & 1u) | (((v.y >> shift) & 1u) << 1) | (((v.z >> shift) & 1u) << 2));
  }
  uint leaf = node - levels[depth].range.x;
  if (leaf >= leafCapacity) return;
  uint base = leaf * DYNGI_LEAF_ATTRIBUTE_INTS;
  // Every fragment counts; the first DYNGI_LEAF_MAX_FRAGMENTS are summed (the 16-bit halves' limit).
  if (atomicAdd(attributes[base + DYNGI_LEAF_COUNT], 1u) >= DYNGI_LEAF_MAX_FRAGMENTS) return;
  uvec3 albedo = uvec3(round(unpackUnorm4x8(f.y).rgb * 255.0));
  uvec3 normal = uvec3(round(unpackSnorm4x8(f.z).xyz * 127.0) + 127.0);
  atomicAdd(attributes[base + DYNGI_LEAF_ALBEDO_RG], albedo.r | (albedo.g << 16));
  atomicAdd(attributes[base + DYNGI_LEAF_ALBEDO_B_NORMAL_X], albedo.b | (normal.x << 16));
  atomicAdd(attributes[base + DYNGI_LEAF_NORMAL_YZ], normal.y | (normal.z << 16));
  if (kEmission && f.w != 0u) {
    vec3 e = min(unpackEmission(f.w) * DYNGI_LEAF_EMISSION_SCALE, vec3(8.0e6));
    for (uint c = 0u; c < 3u; ++c) atomicAdd(attributes[base + DYNGI_LEAF_EMISSION + c], uint(round(e[c])));
    atomicAdd(attributes[base + DYNGI_LEAF_EMITTERS], 1u);
  }
}

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < slots; i += stride) accumulate(i);
}
