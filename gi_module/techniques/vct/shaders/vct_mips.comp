#version 460
// One level of the radiance volume's mip chain from the level below (premultiplied radiance, opacity).
// Isotropic: the mean of the 8 children. Anisotropic (kAnisotropic): the destination is an atlas of six
// slabs side by side along x, one per direction a cone may travel (+x, -x, +y, -y, +z, -z); for slab d
// each of the 4 pairs of children along d's axis is composited front to back as a cone travelling along
// d meets them (front + (1 - front.a) back), and the 4 are averaged: a wall one voxel thick stays opaque
// along its normal at every level instead of fading to 1/2, 1/4, ... (Crassin et al. 2011).
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(constant_id = 0) const bool kAnisotropic = false;
// Isotropic only: each texel's opacity is that of its most opaque axis (the children composited front to
// back along it, averaged over the 4 columns), its radiance that axis' mean composite: a wall one voxel
// thick stays opaque at every level, as in the anisotropic atlas, for one fetch per sample.
layout(constant_id = 1) const bool kOpaqueAxis = false;
// Anisotropic only: the source is the isotropic level 0 (one slab), shared by the six destination slabs:
// one invocation reads its 8 children once and writes the texel in all six.
layout(constant_id = 2) const bool kSharedSource = false;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_SOURCE, rgba16f) uniform readonly image3D source;
layout(set = 0, binding = DYNGI_VCT_MIPS_BINDING_DEST, rgba16f) uniform writeonly image3D dest;
layout(push_constant) uniform Push { DYNGI_VCT_MIPS_PUSH };

vec4 child(uint slab, ivec3 base, ivec3 offset) {
  ivec3 c = base + offset;
  c.x += int(slab * sourceSlabWidth);
  return imageLoad(source, c);
}

vec4 over(vec4 front, vec4 back) { return front + (1.0 - front.a) * back; }

void main() {
  ivec3 size = imageSize(dest);
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p, size))) return;
  if (!kAnisotropic && !kOpaqueAxis) {
    ivec3 base = 2 * p;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 8; ++i) sum += imageLoad(source, base + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    imageStore(dest, p, sum * 0.125);
    return;
  }
  if (!kAnisotropic) {
    ivec3 base = 2 * p;
    vec4 c[8];
    for (int i = 0; i < 8; ++i) c[i] = imageLoad(source, base + ivec3(i & 1, (i >> 1) & 1, i >> 2));
    vec4 best = vec4(0.0);
    for (int axis = 0; axis < 3; ++axis) {
      int step = 1 << axis;  // the child index bit of this axis
      vec4 sum = vec4(0.0);
      for (int i = 0; i < 8; ++i) {
        if ((i & step) != 0) continue;
        vec4 lo = c[i], hi = c[i | step];
        sum += 0.5 * (over(lo, hi) + over(hi, lo));  // both directions along the axis: the same opacity
      }
      sum *= 0.25;
      if (sum.a > best.a) best = sum;
    }
    imageStore(dest, p, best);
    return;
  }
  if (kSharedSource) {
    if (p.x >= int(destSlabWidth)) return;
    ivec3 b = 2 * p;
    vec4 c0 = imageLoad(source, b), c1 = imageLoad(source, b + ivec3(1, 0, 0)), c2 = imageLoad(source, b + ivec3(0, 1, 0)),
         c3 = imageLoad(source, b + ivec3(1, 1, 0)), c4 = imageLoad(source, b + ivec3(0, 0, 1)), c5 = imageLoad(source, b + ivec3(1, 0, 1)),
         c6 = imageLoad(source, b + ivec3(0, 1, 1)), c7 = imageLoad(source, b + ivec3(1, 1, 1));
    int w = int(destSlabWidth);
    // Child i sits at (i & 1, i >> 1 & 1, i >> 2): the pairs along x are (0,1) (2,3) (4,5) (6,7), ...
    imageStore(dest, p, 0.25 * (over(c0, c1) + over(c2, c3) + over(c4, c5) + over(c6, c7)));
    imageStore(dest, p + ivec3(w, 0, 0), 0.25 * (over(c1, c0) + over(c3, c2) + over(c5, c4) + over(c7, c6)));
    imageStore(dest, p + ivec3(2 * w, 0, 0), 0.25 * (over(c0, c2) + over(c1, c3) + over(c4, c6) + over(c5, c7)));
    imageStore(dest, p + ivec3(3 * w, 0, 0), 0.25 * (over(c2, c0) + over(c3, c1) + over(c6, c4) + over(c7, c5)));
    imageStore(dest, p + ivec3(4 * w, 0, 0), 0.25 * (over(c0, c4) + over(c1, c5) + over(c2, c6) + over(c3, c7)));
    imageStore(dest, p + ivec3(5 * w, 0, 0), 0.25 * (over(c4, c0) + over(c5, c1) + over(c6, c2) + over(c7, c3)));
    return;
  }
  uint slab = uint(p.x) / destSlabWidth;
  ivec3 local = ivec3(uint(p.x) % destSlabWidth, p.y, p.z);
  ivec3 base = 2 * local;
  uint axis = slab / 2u;
  bool negative = (slab & 1u) != 0u;
  uint sourceSlab = sourceSlabWidth == 0u ? 0u : slab;
  // The pair along `axis`: the child a cone travelling along +axis meets first has the lower coordinate.
  ivec3 along = axis == 0u ? ivec3(1, 0, 0) : (axis == 1u ? ivec3(0, 1, 0) : ivec3(0, 0, 1));
  ivec3 u = axis == 0u ? ivec3(0, 1, 0) : ivec3(1, 0, 0);
  ivec3 v = axis == 2u ? ivec3(0, 1, 0) : ivec3(0, 0, 1);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j) {
    ivec3 o = (j & 1) * u + (j >> 1) * v;
    vec4 lo = child(sourceSlab, base, o), hi = child(sourceSlab, base, o + along);
    sum += negative ? over(hi, lo) : over(lo, hi);
  }
  imageStore(dest, p, sum * 0.25);
}
