// One cone through the radiance volume, front to back: the GLSL every VCT pass that marches cones shares
// (screen trace, voxel bounce, debug view, test probe). The C++ twin is gi::vctConeCpu (vct_cpu.cpp);
// keep them in step. Positions and distances are in voxel units of the finest level (0..res per axis).
//
// The includer declares, before including:
//   the push members of DYNGI_VCT_CONE_PARAMS (res, maxDistance, aoDistance, coneOffset, coneStep, ...)
//   layout(constant_id = 0) const bool kAnisotropic
// and keeps specialization constant 2 free: it is kVctUnitStep below.
//   uniform sampler3D vctRadiance;  level 0 and (isotropic) its mip chain: premultiplied radiance, opacity
//   uniform sampler3D vctAniso;     (anisotropic) the six-direction atlas of half resolution, with mips
#ifndef DYNGI_VCT_CONE_GLSL
#define DYNGI_VCT_CONE_GLSL
#include "shared/hemisphere.glsl"

const float kVctPi = 3.14159265358979;
const int kVctMaxSteps = DYNGI_VCT_MAX_STEPS;

// The atlas slab for one axis of a direction: +x 0, -x 1, +y 2, -y 3, +z 4, -z 5.
vec4 vctAnisoSlab(vec3 uvw, float lod, uint axis, bool negative, float clampHalf) {
  uint slab = 2u * axis + (negative ? 1u : 0u);
  // Keep the filter footprint inside the slab: x clamped half a texel of the coarser level off its edges.
  float x = clamp(uvw.x, clampHalf, 1.0 - clampHalf);
  return textureLod(vctAniso, vec3((float(slab) + x) / float(DYNGI_VCT_SLABS), uvw.y, uvw.z), lod);
}

// Three slabs as one sample: the step is taken as three parts, one a slab, each the slab's opacity over
// the fraction w of the step (so the transmittance is their weighted geometric mean: a linear blend of
// the opacities would let an oblique cone see a floor as half transparent, along x a thin floor covering
// one column in 2^mip), composited front to back with the most opaque part in front. A wall opaque along
// x then hides what the y and z slabs show of the texel behind it: a coarse texel straddling a thin wall
// showed a cone from the dark room the lit floor under the wall through its y slab (the weighted mean of
// the slabs' colours did). vct_cpu.cpp's sampleCpu takes the parts in the same order. A part is the
// correction a step longer or shorter than its footprint takes (vctPart), over w of a footprint.
//
// Sample s (premultiplied, its opacity over one footprint) taken over `fraction` of a footprint: opacity
// 1 - (1 - a)^fraction, the colour scaled alike. (1 - a is kept off 0: pow(0, 0) is undefined.)
vec4 vctOverFraction(vec4 s, float fraction) {
  float a = 1.0 - pow(max(1.0 - s.a, 1e-6), fraction);
  return vec4(s.a > 1e-6 ? s.rgb * (a / s.a) : vec3(0.0), a);
}
// coneStep is 1: a step's part is its sample, without the pow() (a log2 and an exp2, polynomials on
// lavapipe). Set by the trace, the bounce and the test probe (VoxelConeTracing) at a step of one
// footprint; false elsewhere (the debug view's half steps).
layout(constant_id = 2) const bool kVctUnitStep = false;
// The part of a step `steps` footprints long that sample s (its opacity over one footprint) contributes.
vec4 vctPart(vec4 s, float steps) { return kVctUnitStep ? vec4(s.rgb, clamp(s.a, 0.0, 1.0)) : vctOverFraction(s, steps); }
vec4 vctOver(vec4 front, vec4 back) { return vec4(front.rgb + (1.0 - front.a) * back.rgb, front.a + (1.0 - front.a) * back.a); }
// w: the slabs' fractions of the step, in footprints (the direction's squared components times the step).
vec4 vctCombineSlabs(vec4 sx, vec4 sy, vec4 sz, vec3 w) {
  vec4 px = vctOverFraction(sx, w.x), py = vctOverFraction(sy, w.y), pz = vctOverFraction(sz, w.z);
  vec4 hi = px.a >= py.a ? px : py, lo = px.a >= py.a ? py : px;
  vec4 first = hi.a >= pz.a ? hi : pz, rest = hi.a >= pz.a ? pz : hi;
  vec4 second = rest.a >= lo.a ? rest : lo, third = rest.a >= lo.a ? lo : rest;
  return vctOver(first, vctOver(second, third));
}

// The mip level a sample of footprint 2^mip voxels reads: under DYNGI_VCT_WHOLE_LEVELS_BELOW (footprints
// under 11 voxels: levels up to 8) the nearest whole level, else the footprint's own. lavapipe skips the second level of
// a fetch only where every lane's lod is whole; a diffuse cone's footprints are the same in every lane,
// and most of its steps are near the surface it leaves (its footprint grows by 1.2-1.5 a step there),
// so whole levels there save a fifth of the trace. The step's part is
// taken as before, as the cone's footprint. Farther out the footprint is the cone's, narrowed by
// narrow.x levels (the diffuse cones' VctOptions::farNarrowing; narrow.y is 2^narrow.x): whole levels at
// 11-22 voxels took the Cornell tall box's face to the red wall from 0.81 to 0.66 of the path tracer.
// Returns the level; `steps` becomes the step in footprints of the level read.
float vctReadLevel(float mip, vec2 narrow, inout float steps) {
  bool far = mip >= DYNGI_VCT_WHOLE_LEVELS_BELOW;
  steps *= far ? narrow.y : 1.0;
  return far ? mip - narrow.x : floor(mip + 0.5);
}

// From a footprint of 2 voxels on (mip >= 1), the three atlas slabs the direction faces, weighted by its
// squared components (vctCombineSlabs): the part a step `steps` footprints long takes from them (each
// slab's fraction of it times the step: the step's length costs no pow() of its own).
vec4 vctSampleCoarse(vec3 p, float mip, vec3 dir, float steps, vec2 narrow) {
  vec3 uvw = p / res;
  float level = vctReadLevel(mip, narrow, steps);
  if (!kAnisotropic) return vctPart(textureLod(vctRadiance, uvw, level), steps);
  float lod = max(level - 1.0, 0.0);  // the atlas is half the resolution: its level 0 is a footprint of 2
  float clampHalf = ldexp(1.0, int(ceil(lod))) / res;  // half a texel of the coarser level, in uvw of the slab (a power of two: no exp2)
  vec3 w = dir * dir * steps;
  vec4 sx = vctAnisoSlab(uvw, lod, 0u, dir.x < 0.0, clampHalf), sy = vctAnisoSlab(uvw, lod, 1u, dir.y < 0.0, clampHalf),
       sz = vctAnisoSlab(uvw, lod, 2u, dir.z < 0.0, clampHalf);
  return vctCombineSlabs(sx, sy, sz, w);
}

// The volume at p (voxel units) filtered to a footprint of 2^mip voxels, as seen along `dir`: the part a
// step `steps` footprints long takes from it. Level 0 is isotropic: below mip 1 the anisotropic volume
// blends it with the atlas.
vec4 vctSample(vec3 p, float mip, vec3 dir, float steps, vec2 narrow) {
  if (!kAnisotropic) return vctSampleCoarse(p, mip, dir, steps, narrow);
  vec4 fine = vctPart(textureLod(vctRadiance, p / res, 0.0), steps);
  return mix(fine, vctSampleCoarse(p, mip, dir, steps, narrow), clamp(mip, 0.0, 1.0));
}

// How much of a sample at p (footprint `diameter`) counts: 1 inside the volume, fading to 0 a footprint
// beyond its side. A cone leaving the volume then fades out instead of stopping at whichever sample
// happened to fall outside first, which made neighbouring pixels' cones end a step apart: bands.
float vctInside(vec3 p, float diameter) {
  vec3 beyond = max(max(-p, p - vec3(res)), vec3(0.0));
  return clamp(1.0 - max(beyond.x, max(beyond.y, beyond.z)) / diameter, 0.0, 1.0);
}

// One step of the front-to-back accumulation with its part (vctPart: the sample over the step's length);
// occlusion (AO) weighted by 1 - t / aoDistance.
void vctAccumulate(vec4 part, float t, inout vec3 colour, inout float alpha, inout float occlusion) {
  float a = part.a;
  vec3 c = part.rgb;
  colour += (1.0 - alpha) * c;
  occlusion += (1.0 - occlusion) * a * max(1.0 - t / aoDistance, 0.0);
  alpha += (1.0 - alpha) * a;
}

// Marches a cone of half-angle tangent `tanHalf` from `origin` along unit `dir` for `reach` voxels:
// front-to-back accumulation (colour += (1 - a) c, a += (1 - a) a_voxel), each step the cone's diameter x
// coneStep with the opacity corrected for that step length, until opaque or out of the volume.
// `rise` is how fast the cone leaves the surface it starts from (dot(dir, normal)): the footprint is
// kept under kVctSurfaceClearance times its distance from that surface, since a filtered sample reaches
// about 1.5 texels around it and a wider one would gather the surface's own voxels (self-occlusion and
// self-illumination).
// Returns the radiance arriving along the cone (rgb) and its opacity (a); `occlusion` is the opacity met
// within aoDistance, each sample weighted by 1 - t / aoDistance.
const float kVctSurfaceClearance = DYNGI_VCT_SURFACE_CLEARANCE;
vec4 vctCone(vec3 origin, vec3 dir, float tanHalf, float rise, float reach, float narrowing, out float occlusion) {
  vec2 narrow = vec2(narrowing, exp2(narrowing));
  vec3 colour = vec3(0.0);
  float alpha = 0.0;
  occlusion = 0.0;
  float t = coneOffset;
  bool done = false;
  int i = 0;
  // Three loops: while the footprint is one voxel (level 0 alone), while it is under 2 voxels (level 0
  // blended with the atlas), then with the coarse levels only: lavapipe pays for every fetch a step's
  // code holds, whatever its weight (a single loop would fetch level 0 in every step, and the first steps'
  // three atlas slabs would count for nothing). Every lane of a cone's loop takes the same footprints: a
  // cone's width and rise do not depend on the pixel.
  for (; i < kVctMaxSteps; ++i) {
    float diameter = max(1.0, min(2.0 * tanHalf * t, kVctSurfaceClearance * (coneOffset + rise * t)));
    if (diameter > 1.0) break;
    vec3 p = origin + t * dir;
    float inside = vctInside(p, diameter);
    vctAccumulate(inside * (kAnisotropic ? vctPart(textureLod(vctRadiance, p / res, 0.0), coneStep) : vctSampleCoarse(p, 0.0, dir, coneStep, narrow)), t,
                  colour, alpha, occlusion);
    t += coneStep * diameter;
    if (alpha >= 0.99 || t > reach || inside <= 0.0) {
      done = true;
      break;
    }
  }
  for (; !done && i < kVctMaxSteps; ++i) {
    float diameter = max(1.0, min(2.0 * tanHalf * t, kVctSurfaceClearance * (coneOffset + rise * t)));
    if (diameter >= 2.0) break;
    vec3 p = origin + t * dir;
    float inside = vctInside(p, diameter);
    vctAccumulate(inside * vctSample(p, log2(diameter), dir, coneStep, narrow), t, colour, alpha, occlusion);
    t += coneStep * diameter;
    if (alpha >= 0.99 || t > reach || inside <= 0.0) {
      done = true;
      break;
    }
  }
  for (; !done && i < kVctMaxSteps; ++i) {
    float diameter = min(2.0 * tanHalf * t, kVctSurfaceClearance * (coneOffset + rise * t));
    vec3 p = origin + t * dir;
    float inside = vctInside(p, diameter);
    vctAccumulate(inside * vctSampleCoarse(p, log2(diameter), dir, coneStep, narrow), t, colour, alpha, occlusion);
    t += coneStep * diameter;
    if (alpha >= 0.99 || t > reach || inside <= 0.0) break;
  }
  return vec4(colour, alpha);
}

// Diffuse cone k of n: its half-angle tangent from its elevation on the cosine spiral over all n (its
// cosine z to the normal); returns its weight, its projected solid angle over pi.
float vctDiffuseConeWeight(uint k, uint n, out float z, out float coneTan) {
  float u = (float(k) + 0.5) / float(n);
  z = sqrt(max(1.0 - u, 0.0));
  float cosHalf = max(1.0 - 1.0 / (2.0 * float(n) * max(z, 1e-3)), 0.0);
  coneTan = sqrt(1.0 - cosHalf * cosHalf) / max(cosHalf, 1e-3);
  // A cone tilted by theta keeps its half-angle under 90 - theta degrees (tan <= 0.9 cot theta): wider,
  // it would reach below the horizon and meet the surface it starts from. Its weight shrinks with it.
  coneTan = min(coneTan, 0.9 * z / max(sqrt(u), 1e-4));
  return 2.0 * (1.0 - inversesqrt(1.0 + coneTan * coneTan)) * z;
}

// E / pi at a surface point (voxel units) with unit normal n from the diffuse cones first, first +
// stride, ... of `cones`, scaled by the weight of all the cones over theirs (VctOptions::coneInterleave:
// rows of pixels take turns over the cones, the diffuse filter brings them together); `ao` the mean of
// the marched cones' unoccluded fraction within aoDistance. The elevations are the cosine spiral's over
// all the cones (the apertures follow them); the azimuths step by the golden angle within each set a
// pixel marches, turned by `turn` (a fraction of a turn) about n, so each set is a spiral of its own
// (every other cone of the whole spiral would step 275 degrees, near a quarter turn back: a set's cones
// bunched into a few azimuths, and the filter drew their holes as streaks).
vec3 vctDiffuse(vec3 p, vec3 n, float turn, uint first, uint stride, out float ao) {
  mat3 basis = basisAround(n);
  vec3 origin = p + n * coneOffset;
  vec3 sum = vec3(0.0);
  float occluded = 0.0, marched = 0.0, all = 0.0, z, coneTan;
  for (uint k = 0u; k < cones; ++k) all += vctDiffuseConeWeight(k, cones, z, coneTan);
  for (uint k = first; k < cones; k += stride) {
    float occ;
    float weight = vctDiffuseConeWeight(k, cones, z, coneTan);
    float phi = float(k / stride) * 2.39996323 + 6.28318531 * turn, r = sqrt(max(1.0 - z * z, 0.0));
    sum += weight * vctCone(origin, basis * vec3(r * cos(phi), r * sin(phi), z), coneTan, z, maxDistance, farNarrowing, occ).rgb;
    occluded += weight * occ;
    marched += weight;
  }
  ao = 1.0 - occluded / max(marched, 1e-6);
  return sum * (all / max(marched, 1e-6));
}

#endif
