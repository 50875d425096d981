#pragma once
// Options of the voxel cone tracing technique (`--gi vct`): the one place their defaults live. The table
// (names, ranges, help) is in gi_module/techniques/vct/vct_technique.cpp.
#include <cstdint>

#include "dyngi/gi/options.h"

namespace dyngi::gi {

enum class VctView { Final, Radiance, Opacity, Ao, Indirect, Specular };

struct VctOptions {
  // Diffuse cones, spread over the hemisphere by cosine (equal weights); each cone's aperture covers its
  // share of the hemisphere's solid angle (1/N of 2 pi). A traced pixel marches 1 / coneInterleave of
  // them. 12 (6 a pixel): with the far narrowing below, the Cornell box's tall box keeps the light that
  // arrives between 6 wide cones (docs/QUALITY.md, session 28).
  uint32_t diffuseCones = 12;
  // Rows of traced pixels take turns over the diffuse cones: a pixel in row y marches cones y mod N,
  // y mod N + N, ... (their sum scaled by all the cones' weight over theirs), and the diffuse filter's
  // average over neighbouring rows sees every cone. Rows, not a checkerboard: lavapipe's 8 lanes run a
  // row together, and lanes marching different cones take different footprints (and step counts). The
  // filter's tent weighs the two halves 8 to 8 at radius 3, 13 to 12 at 4; with the filter off (radius
  // 0) every pixel marches every cone.
  uint32_t coneInterleave = 2;
  // Light bounces: 1 is direct light injected into the volume and gathered by the screen cones; each
  // more is a cone-tracing pass over the occupied voxels into a second volume.
  uint32_t bounces = 1;
  // Cones are traced for one pixel in traceScale x traceScale and upsampled with a depth- and
  // normal-aware filter (1: every pixel). 0: the smallest power of two that traces at most 192 x 192
  // pixels (2 at 256^2, 4 at 512^2 and 768^2): the trace is most of the cost, and diffuse light is smooth.
  // A GI budget raises it further.
  uint32_t traceScale = 0;
  // The frames over which every traced pixel gets new cones: 1, 2 or 4 (other values round down to one
  // of these). Each frame traces 1 / traceFrames of them (a 2 x 2 lattice taking turns) and the rest
  // keep last frame's value at their surface point, reprojected; disoccluded ones are filled by the filter
  // and the upsample from the neighbours traced this frame. A still view converges to the every-frame
  // image in traceFrames frames; moving lights and objects lag up to traceFrames - 1 frames. A light
  // switched on or off, a material written, or a light or mesh jumping drops the old values (that frame
  // traces every pixel).
  uint32_t traceFrames = 4;
  // Radius, in traced pixels, of the geometry-aware filter over the traced diffuse light. From 1 up each
  // traced pixel turns its cone set about the normal by its own angle (a golden-ratio dither) and the
  // filter averages the neighbours' sets, so a few cones see the hemisphere through many directions
  // instead of missing the same ones on every pixel of a face (blotches on walls, a face lit by light
  // from between two cones gone dark). 3 is the smallest that leaves no trace of the dither's diagonal
  // pattern; 4 also smooths the faint wisps the rows' halves of the cone set (coneInterleave) leave on
  // a wall at 3 (p99 against every cone on every pixel 0.10 -> 0.07, at no measurable cost; its tent
  // weighs the halves 13 to 12). 0: the same cones everywhere (every pixel marching all of them) and no
  // filter.
  uint32_t diffuseFilterRadius = 4;
  static constexpr uint32_t kMaxDiffuseFilterRadius = 4;  // the filter's taps grow with it: 2 (2r + 1)
  // Opacity and radiance of the mip chain per direction (6 volumes of half resolution, composited front
  // to back along each axis): a thin wall stays opaque at coarse mips, so less light leaks through it,
  // and a one-sided surface shows its light only to the directions that meet its front.
  bool anisotropic = true;
  // Isotropic volumes only: a coarse texel takes the opacity of its most opaque axis (its children
  // composited front to back along it) instead of their mean, so thin walls and floors stay opaque.
  bool opaqueAxisMips = true;
  // The specular cone (aperture from the G-buffer roughness), weighted by the lighting pass with the
  // specular colour (4 percent for dielectrics, the base colour for metals).
  bool specular = true;
  // The roughness from which the specular light is the filtered diffuse light (E / pi) instead of a
  // cone's, blended into it over the DYNGI_VCT_SPECULAR_BLEND (0.2) under it; pixels this rough march no
  // specular cone. A lobe this wide gathers about what the cosine-weighted hemisphere does (a split-sum
  // prefiltered radiance at roughness 1 is the irradiance's), and the diffuse cones have gathered that
  // already; the cone marched at roughness 1 was a 45-degree cone about the normal, a tenth of the trace
  // (docs/BENCHMARKS.md, session 30). With no draw that smooth the trace runs without the cone's code
  // and the lighting takes the diffuse light as the specular (render::SpecularSource::Indirect). Over 1:
  // a cone at every roughness.
  float specularConeBelow = 0.8f;
  // Blend of the injected radiance with the previous frame's, per voxel: the fraction of history kept.
  // A voxel whose radiance changed by more than `temporalResponse` (relative) takes the new value at once,
  // so a light switched off is gone in the frame it went.
  float temporalBlend = 0.5f;
  float temporalResponse = 0.5f;
  // Cone reach, in multiples of the volume's side: the distance a diffuse cone marches before it stops.
  // Past the volume's diagonal (sqrt 3 sides), so a cone from any surface can reach the far side of the
  // volume: with one side, a floor's cones more than 12 degrees off the normal stopped short of a ceiling
  // at the volume's top (an emissive panel there lit the floor at 0.63 of the path tracer). A cone's steps
  // grow with its width, so the extra reach costs a step or two, and it ends at the volume's side anyway.
  float maxDistance = 1.75f;
  // Distance (volume side multiples) over which occlusion counts towards ambient occlusion.
  float aoDistance = 0.15f;
  // Where a cone starts: this many voxels off the surface along the normal (and as far along the cone).
  float coneOffset = 1.0f;
  // Step along a cone in multiples of its diameter; opacity is corrected for it. A little over one
  // footprint: every diffuse cone grows by a fixed factor a step (its surface clearance holds it), so
  // 1.15 takes about a ninth of the steps off while the region errors against the path tracer stay
  // where they were at 1 (docs/QUALITY.md, session 26); from 1.2 the tall box's shadowed face falls
  // to the edge of its band.
  float stepScale = 1.15f;
  // Samples of footprints over 11 voxels (vct_cone.glsl's vctReadLevel) read a level this much under
  // the cone's footprint (2^-this of it wide), the step's part taken over that footprint. A narrower far
  // sample straddles a thin wall less: with 12 diffuse cones the two-room leak is 4.9 percent (8.3 at 0
  // with 6) with every Cornell region within its band; with 6 cones the light that arrives between them
  // is missed (the tall box's shadowed face 0.68; docs/QUALITY.md, session 27).
  float farNarrowing = 0.75f;
  // The mip the `radiance` and `opacity` debug views show.
  uint32_t viewMip = 0;
  VctView view = VctView::Final;  // set by name through the technique, not a table row

  static const OptionTable<VctOptions>& table();
};

}  // namespace dyngi::gi
