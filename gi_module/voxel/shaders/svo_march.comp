#version 460
// Visibility of many segments through the SVO (one thread per segment).
#extension GL_GOOGLE_include_directive : require
#include "voxel_shared.h"
layout(local_size_x = 64) in;
// 0: the march is compiled out (benchmark ceiling: the cost of reading a segment and writing a result).
layout(constant_id = 0) const uint kMarch = 1u;
layout(set = 0, binding = DYNGI_SVO_MARCH_BINDING_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_SVO_MARCH_BINDING_SEGMENTS) readonly buffer Segments { vec4 segments[]; };  // pairs: from, to (world)
layout(set = 0, binding = DYNGI_SVO_MARCH_BINDING_RESULTS) buffer Results { uint results[]; };             // 1 = occluded
#include "svo_traverse.glsl"
layout(push_constant) uniform Push { DYNGI_SVO_MARCH_PUSH };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  vec3 a = (segments[2u * i].xyz - worldToVoxel.xyz) * worldToVoxel.w;
  vec3 b = (segments[2u * i + 1u].xyz - worldToVoxel.xyz) * worldToVoxel.w;
  uint steps;
  if (kMarch == 0u) {  // keep the segment's loads alive (a result no real segment produces)
    results[i] = a.x + b.y > 1e30 ? 1u : 0u;
    return;
  }
  results[i] = svoOccluded(a, b, eps, depth, res, steps) ? 1u : 0u;
}
