#pragma once
// Options of the voxel cone tracing technique (`--gi vct`): the one place their defaults live. The table
// (ranges, help) is in gi_module/techniques/vct/vct_technique.cpp; the measurements behind the defaults
// are in docs/QUALITY.md and docs/BENCHMARKS.md.
#include <cstdint>

#include "dyngi/gi/options.h"

namespace dyngi::gi {

enum class VctView { Final, Radiance, Opacity, Ao, Specular };

struct VctOptions {
  // Diffuse cones, spread over the hemisphere by cosine, each covering its share of the solid angle. 12
  // (6 a pixel with coneInterleave 2): with the far narrowing, fewer lose the light between them.
  uint32_t diffuseCones = 12;
  // Rows of traced pixels take turns over the diffuse cones (row y marches cones y mod N, y mod N + N, ...)
  // and the diffuse filter averages the rows. Rows, not a checkerboard: SIMD lanes along a row then march
  // the same footprints. Without the filter every pixel marches every cone.
  uint32_t coneInterleave = 2;
  // 1: direct light injected and gathered by the screen's cones; each more a cone pass over the voxels.
  uint32_t bounces = 1;
  // The occupied voxels also carry the light that reaches them through the volume, each updated once in
  // this many frames by a cone pass over a part of them (0: off). Injection adds it to their direct light,
  // so each turn adds a bounce: over frames the voxels converge towards every bounce, at 1/N of a bounce
  // pass a frame; a change in the light reaches the carried light N frames a bounce later.
  uint32_t bounceFrames = 0;
  // Without carried bounce light, each occupied voxel also takes the light of emissive surfaces: this
  // many points on them (by power), each shadowed through the SVO, estimate it, and injection adds it, so
  // the surfaces an emitter lights pass its light on as the ones a light lights do (0: off, the cones
  // then see the emitters alone). 1, 2 or 4: the cones' mips average many voxels' few points.
  uint32_t emitterSamples = 2;
  // Frames over which every voxel's emitter light is updated once after something moved, a part of the
  // voxels each: an occluder moving in front of an emitter moves its shadow in the voxels that many
  // frames later; a still scene keeps the light and skips the pass. A changed emitter, a moved object's
  // new voxels and the first frame are updated at once.
  uint32_t emitterFrames = 8;
  // One pixel in traceScale^2 is traced, then upsampled by depth and normal (1: every pixel; 0: the
  // smallest power of two tracing at most 192^2 pixels). Diffuse light is smooth and the trace is most
  // of the cost. A GI budget raises it further.
  uint32_t traceScale = 0;
  // Frames over which every traced pixel gets new cones (1, 2 or 4): the others are last frame's,
  // reprojected. A still view is the every-frame image after that many frames; motion lags up to
  // traceFrames - 1 frames, and a light switched or a jump traces every pixel at once (under a GI budget
  // only this frame's share, the rest upsampled from it until their turn).
  uint32_t traceFrames = 4;
  // Frames over which the voxels' radiance update (injection and mips) is spread, one part of the voxels
  // each (1 to 4): a still light gives the same volume; a change reaches every voxel that many frames
  // later. A GI budget raises it further.
  uint32_t radianceFrames = 1;
  // Radius, in traced pixels, of the geometry-aware filter over the diffuse light. From 1 each traced
  // pixel turns its cone set by its own angle and the filter averages the neighbours' sets, so a few
  // cones see many directions instead of missing the same ones all over a face. 0: fixed cones, no filter.
  uint32_t diffuseFilterRadius = 4;
  static constexpr uint32_t kMaxDiffuseFilterRadius = 4;  // the filter's taps grow with it: 2 (2r + 1)
  // A mip chain per direction (six slabs, composited front to back along each axis): a thin wall stays
  // opaque at coarse mips, and a one-sided surface shows its light only to the directions facing it.
  bool anisotropic = true;
  // Isotropic only: a coarse texel takes its most opaque axis' opacity, not the mean, so thin walls hold.
  bool opaqueAxisMips = true;
  // The specular cone (aperture from the G-buffer roughness), weighted by the lighting pass.
  bool specular = true;
  // From this roughness the specular light is the filtered diffuse light (E / pi), blended in over the
  // 0.2 below it: a lobe that wide gathers about the cosine-weighted hemisphere the diffuse cones have
  // gathered already. Over 1: a cone at every roughness.
  float specularConeBelow = 0.8f;
  // Per voxel, the fraction of last frame's injected radiance kept; a change over temporalResponse
  // (relative) takes the new value at once, so a light switched off is gone in that frame.
  float temporalBlend = 0.5f;
  float temporalResponse = 0.5f;
  // Cone reach in volume sides: past the diagonal (sqrt 3), so a cone from any surface reaches the far side.
  float maxDistance = 1.75f;
  // Reach of ambient occlusion, in volume sides.
  float aoDistance = 0.15f;
  // Where a cone starts: this many voxels off the surface.
  float coneOffset = 1.0f;
  // Step along a cone in cone diameters (opacity corrected for it): 1.15 takes a ninth of the steps off
  // while every Cornell region stays in its band.
  float coneStep = 1.15f;
  // Samples of footprints over 11 voxels read a footprint 2^-this of the cone's: a narrower far sample
  // straddles a thin wall less (the two-room leak under 5 percent with 12 cones).
  float farNarrowing = 0.75f;
  // The mip the `radiance` and `opacity` debug views show.
  uint32_t viewMip = 0;
  VctView view = VctView::Final;  // set by name through the technique, not a table row

  static const OptionTable<VctOptions>& table();
};

}  // namespace dyngi::gi
