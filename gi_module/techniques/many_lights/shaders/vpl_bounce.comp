#version 460
// Multi-bounce VPLs: each VPL of bounce b-1 shoots one cosine-distributed (Halton) direction through the
// voxel scene; where it lands, a VPL of bounce b reflects parent flux x the voxel's albedo. The bounce
// tail's probes, with a stride, come from one parent in each run of that many, standing for the run.
#extension GL_GOOGLE_include_directive : require
#include "many_lights_shared.h"
#include "shared/bounce_tail.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_VPL_BOUNCE_BINDING_VPLS) buffer Vpls { GpuVpl vpls[]; };
layout(set = 0, binding = DYNGI_VPL_BOUNCE_BINDING_NODES) readonly buffer Nodes { uint nodes[]; };
layout(set = 0, binding = DYNGI_VPL_BOUNCE_BINDING_NODE_CELLS) readonly buffer NodeCells { uint nodeCells[]; };
layout(set = 0, binding = DYNGI_VPL_BOUNCE_BINDING_VOXEL_ATTRIBUTES, rgba32ui) uniform readonly uimage3D voxelAttributes;
#include "svo_traverse.glsl"
#include "leaf_attributes.glsl"
#include "svo_morton.glsl"
layout(push_constant) uniform Push { DYNGI_VPL_BOUNCE_PUSH };

float halton(uint i, uint base) {
  float f = 1.0, r = 0.0;
  while (i > 0u) { f /= float(base); r += f * float(i % base); i /= base; }
  return r;
}

// A uniform number in [0, 1) from the seed and a Halton dimension.
float rotation(uint s, uint d) {
  uint x = s * 0x9E3779B9u + d * 0x85EBCA6Bu;
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x >> 8) * (1.0 / 16777216.0);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= (count + parentStride - 1u) / parentStride) return;
  GpuVpl parent = vpls[parentFirst + bounceTailChosenInRun(i, parentStride, count)];
  float runLength = float(bounceTailRunLength(i, parentStride, count));
  GpuVpl child;
  child.position = vec4(0.0, 0.0, 0.0, -1.0);
  child.normal = vec4(0.0, 1.0, 0.0, parent.normal.w);
  child.flux = vec4(0.0);
  uint childIndex = parentFirst + count + i;
  if (parent.position.w < 0.0 || parent.flux.w <= 0.0) { vpls[childIndex] = child; return; }
  vec3 n = parent.normal.xyz;
  // Each bounce its own pair of Halton dimensions (bases 2 and 3, then 5 and 7, ...): a path's directions
  // are then independent from bounce to bounce. (The same point shifted per bounce, as before, kept them
  // correlated: the third bounce put 10x the path tracer's share of light on the short box's front.)
  const uint kBases[8] = uint[](2u, 3u, 5u, 7u, 11u, 13u, 17u, 19u);
  uint dim = 2u * min(bounce - 1u, 3u);
  // Each pair turned by the seed (a Cranley-Patterson rotation): the seed changes the directions too, not
  // only the RSM samples, so seeds give independent estimates. Without it every seed shot the same
  // directions, and their image kept one fixed error: the short box's front 12% dark against the path
  // tracer (3 bounces, the mean of seeds 1-3; 5% with the rotation).
  float u1 = fract(halton(i + 1u, kBases[dim]) + rotation(seed, dim));
  float u2 = fract(halton(i + 1u, kBases[dim + 1u]) + rotation(seed, dim + 1u));
  float r = sqrt(u1), phi = 6.2831853 * u2;
  vec3 t = abs(n.x) > 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 b1 = normalize(cross(n, t)), b2 = cross(n, b1);
  vec3 dir = normalize(r * cos(phi) * b1 + r * sin(phi) * b2 + sqrt(max(0.0, 1.0 - u1)) * n);
  vec3 o = (parent.position.xyz - worldToVoxel.xyz) * worldToVoxel.w + n * lift;
  float tHit;
  uint steps;
  uint node = svoFirstHit(o, dir, 0.0, 1e30, depth, res, tHit, steps);
  if (node != 0xFFFFFFFFu) {
    LeafAttributes attr = voxelAttributesAt(svoCellOfMortonCode(SVO_NODE_CELL(nodeCells, node)));
    vec3 albedo = attr.albedo;
    vec3 vn = attr.normalSum;
    vn = length(vn) > 0.0 ? normalize(vn) : -dir;
    if (dot(vn, dir) > 0.0) vn = -vn;  // face the incoming ray
    vec3 hitVoxel = o + dir * tHit;
    child.position = vec4(hitVoxel / worldToVoxel.w + worldToVoxel.xyz, float(bounce));
    child.normal = vec4(vn, parent.normal.w);
    vec3 flux = parent.flux.rgb * albedo * runLength;
    child.flux = vec4(flux, dot(flux, vec3(0.2126, 0.7152, 0.0722)));
  }
  vpls[childIndex] = child;
}
