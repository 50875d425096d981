#version 460
// SVO build, step 1: every voxel fragment marks its cell in the occupancy pyramid at every level, finest
// first (DYNGI_SVO_LEVEL_BASE). A cell found marked already has its coarser cells marked (or being
// marked by the invocation that set it), so most fragments stop after a level or two. Reads the entity
// ranges in place, one chunk of slots per workgroup (the C++ side cuts them from the ranges it wants
// marked: the static entities' into the static pyramid, the moving ones' into a copy of it), up to the
// range's fragment count (DYNGI_SVO_CHUNK_END).
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
#include "svo_morton.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_SVO_MARK_BINDING_FRAGMENTS) readonly buffer Fragments { uvec4 fragments[]; };
layout(set = 0, binding = DYNGI_SVO_MARK_BINDING_OCCUPANCY) buffer Occupancy { uint occupancy[]; };
layout(set = 0, binding = DYNGI_SVO_MARK_BINDING_CHUNKS) readonly buffer Chunks { uvec4 chunks[]; };  // DYNGI_SVO_CHUNK
layout(set = 0, binding = DYNGI_SVO_MARK_BINDING_COUNTERS) readonly buffer Counters { uint counters[]; };
layout(push_constant) uniform Push { DYNGI_SVO_MARK_PUSH };
void markFragment(uint i) {
  uint c = fragments[i].x;
  if (c == DYNGI_VOXEL_EMPTY) return;
  uint code = svoMortonCode(uvec3(c & 1023u, (c >> 10) & 1023u, (c >> 20) & 1023u));
  for (int l = int(depth); l >= 0; --l) {
    uint index = DYNGI_SVO_LEVEL_BASE(uint(l)) + (code >> (3u * (depth - uint(l))));
    uint bit = 1u << (index & 31u);
    if ((occupancy[index >> 5] & bit) != 0u) return;
    atomicOr(occupancy[index >> 5], bit);
  }
}
void main() {
  uvec4 chunk = chunks[firstChunk + gl_WorkGroupID.x];
  uint end = DYNGI_SVO_CHUNK_END(chunk, counters);
  for (uint i = chunk.x + gl_LocalInvocationIndex; i < end; i += gl_WorkGroupSize.x) markFragment(i);
}
