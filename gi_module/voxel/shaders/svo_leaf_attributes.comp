#version 460
// Accumulates each fragment's albedo, normal and emission into its leaf (integer atomics; the layout is
// DYNGI_LEAF_* in gi_gpu_types.h, read through leaf_attributes.glsl), sums that svo_voxel_attributes.comp
// turns into the voxel attributes image. Reads the chunks of the ranges SvoBuilder wants summed, one a
// workgroup, as the mark pass does: the moving entities' in every build (each leaf listed at its first
// fragment), the static ones' once when the static set changes.
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
#include "subgroup_append.glsl"
#include "svo_morton.glsl"
layout(local_size_x = 64) in;
// False when no fragment emits (VoxelScene::fragmentsEmit): the emission sums stay 0 without the
// atomics, which lavapipe would run masked for every fragment.
layout(constant_id = 0) const bool kEmission = true;
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS) readonly buffer Levels { SvoLevel levels[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES) buffer Attributes { uint attributes[]; };  // DYNGI_LEAF_ATTRIBUTE_INTS per leaf
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_CHUNKS) readonly buffer Chunks { uvec4 chunks[]; };  // DYNGI_SVO_CHUNK
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_COUNTERS) readonly buffer Counters { uint counters[]; };
layout(set = 0, binding = DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_MOVING) buffer Moving { uvec4 header; uvec4 entries[]; } moving;
layout(push_constant) uniform Push { DYNGI_SVO_LEAF_ATTRIBUTES_PUSH };

vec3 unpackEmission(uint e) {
  vec4 v = unpackUnorm4x8(e);
  return e == 0u ? vec3(0.0) : v.rgb * exp2(round(v.a * 255.0) - 8.0);
}

// Adds fragment i to its leaf; true for the leaf's first fragment of this pass (`leaf`, `voxel`: which).
bool accumulate(uint i, out uint leaf, out uvec3 v) {
  leaf = 0u;
  uvec4 f = fragments[i];
  v = uvec3(f.x & 1023u, (f.x >> 10) & 1023u, (f.x >> 20) & 1023u);
  if (f.x == DYNGI_VOXEL_EMPTY) return false;
  // Its leaf: down from the root.
  uint node = 0u;
  for (uint l = 0u; l < depth; ++l) {
    uint g = nodes[node] & DYNGI_SVO_GROUP_MASK;
    if (g == 0u) return false;  // its branch overflowed the node pool
    uint shift = depth - 1u - l;
    node = 8u * g + (((v.x >> shift) & 1u) | (((v.y >> shift) & 1u) << 1) | (((v.z >> shift) & 1u) << 2));
  }
  leaf = node - levels[depth].range.x;
  if (leaf >= leafCapacity) return false;
  uint base = leaf * DYNGI_LEAF_ATTRIBUTE_INTS;
  // Every fragment counts; the first DYNGI_LEAF_MAX_FRAGMENTS are summed (the 16-bit halves' limit).
  uint before = atomicAdd(attributes[base + DYNGI_LEAF_COUNT], 1u);
  if (before >= DYNGI_LEAF_MAX_FRAGMENTS) return false;
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
  return before == 0u;
}

void main() {
  // A chunk is at most DYNGI_SVO_ITEMS_PER_INVOCATION slots an invocation: a uniform trip count, for the
  // subgroup append inside.
  uvec4 chunk = chunks[firstChunk + gl_WorkGroupID.x];
  // The rounds past the range's fragments are left out (a moving range's slack is about half its slots):
  // lavapipe runs a round whose lanes are all past the end, masked, at the cost of a full one. The break
  // is the workgroup's together, so the append stays in uniform control flow.
  uint end = DYNGI_SVO_CHUNK_END(chunk, counters);
  for (uint r = 0u; r < DYNGI_SVO_ITEMS_PER_INVOCATION; ++r) {
    uint round = chunk.x + r * gl_WorkGroupSize.x;
    if (round >= end) break;
    uint i = round + gl_LocalInvocationIndex, leaf;
    uvec3 v;
    bool first = i < end && accumulate(i, leaf, v);
    if (listLeaves == 0u) continue;
    // The leaf's first fragment lists it (svo_voxel_attributes.comp merges it): one atomic a subgroup.
    uint k;
    DYNGI_SUBGROUP_APPEND(moving.header.w, first, k)
    if (first && k < uint(moving.entries.length()) / 2u) moving.entries[2u * k] = uvec4(leaf, svoMortonCode(v), 0u, 0u);
  }
}
