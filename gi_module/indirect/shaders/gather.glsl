// Interleaved indirect gather, shared by the VPL techniques: pixel (x, y) belongs to sub-image
// s = (x mod K) + K (y mod K) and gathers only VPLs s, s + K^2, ...; one workgroup covers pixels of one
// sub-image, so its threads walk the same VPLs (coherent VPL and SVO reads). E = sum flux G V with
// G = cos_x cos_y / max(B, d^2) and V from the SVO-restart march or precomputed bits; dim or back-facing
// VPLs are skipped before marching. The light is (N / n_s) E / pi^2 for a sub-image that gathered n_s of
// the N VPLs it stands for (N = estimatedCount; n_s = N / K^2 when N is a multiple of K^2): every
// sub-image estimates the full sum's E / pi (what the lighting pass multiplies by albedo), so the K x K
// filter's average does too, even where an edge leaves it only some sub-images.
//
// A gather shader (gather.comp, or a technique's own such as the temporal technique's
// temporal_gather.comp) includes this file, may declare bindings from DYNGI_GATHER_FIRST_TECHNIQUE_BINDING
// on and push constants after GatherPush (define GATHER_EXTRA_PUSH before the include), and writes its
// main() around gatherPixel().
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "voxel_shared.h"
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_GATHER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_GATHER_BINDING_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_GATHER_BINDING_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_GATHER_BINDING_VPLS) readonly buffer Vpls { GpuVpl vpls[]; };
layout(set = 0, binding = DYNGI_GATHER_BINDING_SVO_NODES) readonly buffer Nodes { uint nodes[]; };
// filter_input.glsl's packing; read by a chunk after the first (GatherPush::chunkBegin).
layout(set = 0, binding = DYNGI_GATHER_BINDING_OUTPUT, rgba32ui) uniform uimage2D outRaw;
layout(set = 0, binding = DYNGI_GATHER_BINDING_VISIBILITY_BITS) readonly buffer VisibilityBits { uint visibleBits[]; };  // visibility mode 2
layout(set = 0, binding = DYNGI_GATHER_BINDING_CLAMP_SPREAD) readonly buffer ClampSpread { vec2 clampSpreadTable[]; };  // (I, N)
#ifndef GATHER_EXTRA_PUSH
#define GATHER_EXTRA_PUSH
#endif
layout(push_constant) uniform Push { GatherPush pc; GATHER_EXTRA_PUSH };
// A pipeline whose dispatches are chunks of a larger gather (GatherPush::chunkBegin); the plain one
// leaves out the chunks' extra image load and store (lavapipe runs a branch's body either way).
layout(constant_id = 0) const bool kGatherChunked = false;
#include "svo_traverse.glsl"
#include "filter_input.glsl"
#include "shared/clamp_spread.h"

const float PI = 3.14159265358979;

// (I, N) of the clamp spread at (eta, c), bilinear between the table's samples (clampSpreadLookup's twin).
vec2 clampSpreadAt(float eta, float c) {
  const int E = DYNGI_CLAMP_SPREAD_ETA_CELLS, C = DYNGI_CLAMP_SPREAD_COS_CELLS;
  vec2 p = clampSpreadCoords(eta, c);
  int e0 = min(int(p.x), E - 2), c0 = min(int(p.y), C - 2);
  vec2 f = p - vec2(e0, c0);
  int i = e0 + E * c0;
  return mix(mix(clampSpreadTable[i], clampSpreadTable[i + 1], f.x), mix(clampSpreadTable[i + E], clampSpreadTable[i + E + 1], f.x), f.y);
}

// Whether the screen shows the receiver's plane (through x, normal nx) where the clamp spread lays a
// VPL's dropped light: at y's foot on it, moved half the clamp's reach along the plane the way y faces
// (up the wall from a floor VPL's foot). The spread takes the plane to run on past x; a box's face does
// not, and a VPL on the floor beside the box sits on its plane's extension, where the clamp dropped its
// light on nothing: spread, that light smeared along the face's base. False only when the screen sees
// past that point (the floor or a far wall beside the box); off screen or hidden, the plane is assumed.
bool spreadPlaneShown(vec3 x, vec3 nx, vec3 y, vec3 ny, float clampB) {
  vec3 along = ny - dot(ny, nx) * nx;
  float l2 = dot(along, along);
  vec3 probe = y - dot(y - x, nx) * nx + (l2 > 1e-4 ? along * inversesqrt(l2) : vec3(0.0)) * (0.5 * sqrt(clampB));
  vec4 clip = frame.viewProj * vec4(probe, 1.0);
  if (clip.w <= 0.0) return true;
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  ivec2 q = ivec2((clip.xy / clip.w * 0.5 + 0.5) * vec2(size));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return true;
  vec4 seen = imageLoad(gPosition, q);
  if (seen.w == 0.0) return false;  // background where the plane should be
  float depth = viewDepthOf(probe), tolerance = max(0.25 * sqrt(clampB), 0.01 * depth);
  if (abs(dot(seen.xyz - x, nx)) < tolerance) return true;
  return viewDepthOf(seen.xyz) < depth - tolerance;  // something in front hides the point: cannot tell
}

// Light from the set's VPL i (the m-th this pixel gathers) at surface point x with normal nx (xv: x in
// voxel units, lifted): flux G V, or 0 for an absent, dim or back-facing VPL or one beyond the count.
vec3 vplLight(uint i, uint m, vec3 x, vec3 nx, vec3 xv, float threshold, uint bitBase) {
  if (i >= pc.chunkEnd) return vec3(0.0);
  GpuVpl v = vpls[pc.firstVpl + i];
  if (v.position.w < 0.0 || v.flux.w <= threshold) return vec3(0.0);
  vec3 d = v.position.xyz - x;
  float d2 = dot(d, d);
  if (d2 <= 0.0) return vec3(0.0);
  vec3 w = d * inversesqrt(d2);
  float cx = dot(nx, w), cy = -dot(v.normal.xyz, w);
  if (cx <= 0.0 || cy <= 0.0) return vec3(0.0);
  const float clampB = pc.tailBounce > 0u && v.position.w >= float(pc.tailBounce) ? pc.distanceClamp * DYNGI_TAIL_CLAMP_SCALE : pc.distanceClamp;
  float g = cx * cy / max(clampB, d2);
  // The light the clamp drops, given back near where it lands (shared/clamp_spread.h).
  if (pc.clampSpread > 0.0) {  // the same for every lane
    float c = -dot(v.normal.xyz, nx), stretch = clampSpreadStretch(c, pc.clampSpread);
    vec3 t = cross(nx, v.normal.xyz);
    float along = dot(d, t), along2 = along * along / max(dot(t, t), 1e-8);
    float bump = clampSpreadBump(d2, along2, clampB, stretch);
    if (bump > 0.0 && spreadPlaneShown(x, nx, v.position.xyz, v.normal.xyz, clampB))  // few VPLs are within reach
      g += clampSpreadG(clampSpreadAt(cx * sqrt(d2) * inversesqrt(clampB), c), bump, d2, cy, clampB, stretch);
  }
  if (pc.visibility == DYNGI_VISIBILITY_BITS) {
    uint bit = bitBase + m;
    if ((visibleBits[bit >> 5] & (1u << (bit & 31u))) == 0u) return vec3(0.0);
  } else if (pc.visibility == DYNGI_VISIBILITY_SVO) {
    vec3 yv = (v.position.xyz - pc.worldToVoxel.xyz) * pc.worldToVoxel.w + v.normal.xyz * pc.liftVoxels;
    uint steps;
    if (svoOccluded(xv, yv, 1e-3, pc.svoDepth, pc.voxelResolution, steps)) return vec3(0.0);
  }
  return v.flux.rgb * g;
}

// Gathers this invocation's pixel: false when it lies outside the image. `depth` is -1 where the
// G-buffer is empty (the light is then 0).
bool gatherPixel(out ivec2 px, out vec3 light, out float depth, out uvec2 packedNormal) {
  uint K = pc.interleave;
  uint s = gl_GlobalInvocationID.z;
  px = ivec2(gl_GlobalInvocationID.xy) * int(K) + ivec2(s % K, s / K);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return false;
  vec4 pos = imageLoad(gPosition, px);
  vec3 e = vec3(0.0), nx = vec3(0.0, 0.0, 1.0);
  depth = -1.0;
  uint K2 = K * K;
  if (pos.w != 0.0) {
    vec3 x = pos.xyz;
    depth = viewDepthOf(x);
    nx = normalize(imageLoad(gNormal, px).xyz);
    vec3 xv = (x - pc.worldToVoxel.xyz) * pc.worldToVoxel.w + nx * pc.liftVoxels;
    // Importance sampling gives every first-bounce VPL the same luminance; the threshold is relative to it.
    float threshold = pc.luminanceThreshold * vpls[pc.firstVpl].flux.w;
    uint bitBase = pc.firstBit + (uint(px.y) * frame.sizeAndCount.x + uint(px.x)) * pc.bitsPerPixel;
    // A do-while: lavapipe runs a for loop's body once more, masked, before it sees every lane has left;
    // checking at the end saves that pass (a gather and an SVO march step per pixel).
    uint i = pc.chunkBegin + s, m = pc.chunkBegin / K2;
    do {
      e += vplLight(i, m, x, nx, xv, threshold, bitBase);
      i += K2;
      ++m;
    } while (i < pc.chunkEnd);
  }
  const uint gathered = s < pc.vplCount ? (pc.vplCount - s + K2 - 1u) / K2 : 0u;  // n_s
  light = gathered > 0u ? (float(pc.estimatedCount) / float(gathered)) * e / (PI * PI) : vec3(0.0);
  if (kGatherChunked && pc.chunkBegin > 0u) light += filterLight(imageLoad(outRaw, px));  // the earlier chunks' share
  packedNormal = packFilterNormal(nx);
  return true;
}
