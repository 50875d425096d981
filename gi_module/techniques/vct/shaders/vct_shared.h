// Voxel cone tracing's C++/GLSL layouts: the passes over the occupied voxels and the screen, the cone
// march's constants (gi_module/techniques/vct/).
#ifndef DYNGI_VCT_SHARED_H
#define DYNGI_VCT_SHARED_H

#include "voxel_shared.h"

DYNGI_GPU_NAMESPACE_BEGIN

// Voxel cone tracing (techniques/vct/): the passes over the occupied voxels (SVO leaves) and the screen.
// vct_inject: direct light and emission of each occupied voxel into the radiance volume
#define DYNGI_VCT_INJECT_BINDING_LEAF_LIST 0  /* the SVO's compacted leaf list */
#define DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES 1
#define DYNGI_VCT_INJECT_BINDING_LIGHTS 2
#define DYNGI_VCT_INJECT_BINDING_SHADOW_MATRICES 3
#define DYNGI_VCT_INJECT_BINDING_SHADOW_MAPS 4
#define DYNGI_VCT_INJECT_BINDING_DIRECT 5  /* read (last frame's, the temporal blend's history) and written in place */
#define DYNGI_VCT_INJECT_BINDING_RADIANCE 6
#define DYNGI_VCT_INJECT_BINDING_CHANGED_BOXES 7  /* vct_parts.glsl */
#define DYNGI_VCT_INJECT_BINDING_CARRIED 8  /* the light the voxels carry (bounce light: VctOptions::bounceFrames; or the emitters'), added to level 0 */
// vct_emitter_light: per occupied voxel, the light emissive surfaces send it, sampled with SVO visibility,
// into the carried image (when no bounce light is carried: VctOptions::emitterSamples)
#define DYNGI_VCT_EMITTER_BINDING_LEAF_LIST 0
#define DYNGI_VCT_EMITTER_BINDING_VOXEL_ATTRIBUTES 1
#define DYNGI_VCT_EMITTER_BINDING_OUT 2
#define DYNGI_VCT_EMITTER_BINDING_CHANGED_BOXES 3
#define DYNGI_VCT_EMITTER_BINDING_PREVIOUS_OCCUPANCY 4
#define DYNGI_VCT_EMITTER_BINDING_SVO_NODES 5
#define DYNGI_VCT_EMITTER_BINDING_POINTS 6  /* VctEmitterPoint[DYNGI_VCT_EMITTER_POINTS] */
// The points sampled on the emitters each frame (by power); each voxel takes an evenly spaced subset.
#define DYNGI_VCT_EMITTER_POINTS 256
// Points a voxel takes at most: an invocation's 16 leaves (DYNGI_SVO_ITEMS_PER_INVOCATION) then march 64
// SVO segments, what the gather allows a pixel (DYNGI_GATHER_MAX_VPLS_PER_PIXEL), under lavapipe's shared
// loop-iteration limit; past it the marches stop part way and report points hidden that are not.
#define DYNGI_VCT_EMITTER_MAX_SAMPLES 4
// vct_clear_stale: the per-voxel state of the cells that emptied since the last SVO build, zeroed
#define DYNGI_VCT_CLEAR_BINDING_RUNS 0              /* uvec2 (SVO level, first Morton code) per run of 32 cells */
#define DYNGI_VCT_CLEAR_BINDING_PREVIOUS_OCCUPANCY 1  /* the build before's pyramid */
#define DYNGI_VCT_CLEAR_BINDING_OCCUPANCY 2           /* the last build's */
#define DYNGI_VCT_CLEAR_BINDING_RADIANCE 3            /* level 0 */
#define DYNGI_VCT_CLEAR_BINDING_DIRECT 4
#define DYNGI_VCT_CLEAR_BINDING_ATLAS 5               /* the anisotropic atlas' level 0 (anisotropic only) */
#define DYNGI_VCT_CLEAR_BINDING_ATLAS_1 6             /* its level 1 */
#define DYNGI_VCT_CLEAR_BINDING_CARRIED 7             /* the carried light (the direct radiance again when there is none) */
// vct_bounce: one more bounce per occupied voxel (cones over the radiance volume), then vct_commit; or
// the carried bounce light of this frame's part of the voxels (OUT: the carried light, DIRECT unused)
#define DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST 0  /* the SVO's compacted leaf list */
#define DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES 1
#define DYNGI_VCT_BOUNCE_BINDING_DIRECT 2
#define DYNGI_VCT_BOUNCE_BINDING_RADIANCE 3
#define DYNGI_VCT_BOUNCE_BINDING_ANISO 4
#define DYNGI_VCT_BOUNCE_BINDING_OUT 5
#define DYNGI_VCT_BOUNCE_BINDING_CHANGED_BOXES 6  /* the carried light's: vct_parts.glsl */
#define DYNGI_VCT_BOUNCE_BINDING_PREVIOUS_OCCUPANCY 7  /* the build before's pyramid: which leaves in the boxes are new */
// vct_mips: one level of the radiance mip chain (isotropic) or of the six-direction atlas
#define DYNGI_VCT_MIPS_BINDING_SOURCE 0
#define DYNGI_VCT_MIPS_BINDING_DEST 1
#define DYNGI_VCT_MIPS_BINDING_SEEN 2
// The anisotropic atlas is built over the SVO's occupied nodes only (the rest of it is cleared):
#define DYNGI_VCT_MIPS_BINDING_NODE_CELLS 3
#define DYNGI_VCT_MIPS_BINDING_LEVELS 4
#define DYNGI_VCT_MIPS_BINDING_LEAF_LIST 5  /* the parts of a radiance update spread over frames (vct_parts.glsl) */
#define DYNGI_VCT_MIPS_BINDING_CHANGED_BOXES 6
// vct_trace: the screen's cones; vct_upsample: to full resolution
#define DYNGI_VCT_TRACE_BINDING_FRAME 0
#define DYNGI_VCT_TRACE_BINDING_G_POSITION 1
#define DYNGI_VCT_TRACE_BINDING_G_NORMAL 2
#define DYNGI_VCT_TRACE_BINDING_RADIANCE 3
#define DYNGI_VCT_TRACE_BINDING_ANISO 4
#define DYNGI_VCT_TRACE_BINDING_OUT_DIFFUSE 5
#define DYNGI_VCT_TRACE_BINDING_OUT_SPECULAR 6
// vct_reproject: the traced pixels not traced this frame, from last frame's (trace amortized over frames)
#define DYNGI_VCT_REPROJECT_BINDING_FRAME 0
#define DYNGI_VCT_REPROJECT_BINDING_G_POSITION 1
#define DYNGI_VCT_REPROJECT_BINDING_G_NORMAL 2
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_DIFFUSE 3
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SPECULAR 4
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SURFACE 5
#define DYNGI_VCT_REPROJECT_BINDING_OUT_DIFFUSE 6
#define DYNGI_VCT_REPROJECT_BINDING_OUT_SPECULAR 7
#define DYNGI_VCT_REPROJECT_BINDING_OUT_SURFACE 8
#define DYNGI_VCT_UPSAMPLE_BINDING_G_POSITION 0
#define DYNGI_VCT_UPSAMPLE_BINDING_G_NORMAL 1
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_DIFFUSE 2
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_SPECULAR 3
#define DYNGI_VCT_UPSAMPLE_BINDING_OUT_DIFFUSE 4
#define DYNGI_VCT_UPSAMPLE_BINDING_OUT_SPECULAR 5
#define DYNGI_VCT_UPSAMPLE_BINDING_FRAME 6
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_SURFACE 7
#define DYNGI_VCT_FILTER_BINDING_FRAME 0
#define DYNGI_VCT_FILTER_BINDING_SURFACE 1
#define DYNGI_VCT_FILTER_BINDING_IN 2
#define DYNGI_VCT_FILTER_BINDING_OUT 3
// vct_debug: views over the HDR image
#define DYNGI_VCT_DEBUG_BINDING_FRAME 0
#define DYNGI_VCT_DEBUG_BINDING_RADIANCE 1
#define DYNGI_VCT_DEBUG_BINDING_ANISO 2
#define DYNGI_VCT_DEBUG_BINDING_INDIRECT 3
#define DYNGI_VCT_DEBUG_BINDING_SPECULAR 4
#define DYNGI_VCT_DEBUG_BINDING_OUT_HDR 5
// vct_cone_probe (tests): cones along given rays
#define DYNGI_VCT_PROBE_BINDING_RAYS 0
#define DYNGI_VCT_PROBE_BINDING_RADIANCE 1
#define DYNGI_VCT_PROBE_BINDING_ANISO 2
#define DYNGI_VCT_PROBE_BINDING_RESULTS 3
// The six directions of the anisotropic atlas, in slab order: a cone travelling along +x reads slab 0.
#define DYNGI_VCT_SLABS 6u
// The cone march (vct_cone.glsl and its C++ twin, vct_cpu.cpp): most steps a cone takes, and its
// footprint's largest fraction of its distance from the surface it left.
#define DYNGI_VCT_MAX_STEPS 160
#define DYNGI_VCT_SURFACE_CLEARANCE 0.5
// Footprints under 2^this voxels (11) read the nearest whole mip level (vctReadLevel): levels up to 8 voxels.
#define DYNGI_VCT_WHOLE_LEVELS_BELOW 3.5
// The atlas' first level (vct_mips.comp and vctAnisoDownsample): a one-sided voxel whose normal's
// component along an axis is under this in size is parallel to that axis, seen from both of its sides
// (so that the normal's rounding does not hide a floor from one side).
#define DYNGI_VCT_PARALLEL 0.1
// Which cones see an occupied voxel's radiance, in the alpha of the direct-radiance volume (vct_inject.comp
// writes it, the atlas' first level reads it: vct_seen.glsl, vctSeenMask in vct_cpu.cpp): 1 + a 6-bit
// mask, 0 for an empty voxel. Bit 2 axis is set when a cone travelling along +axis meets the voxel's
// front, bit 2 axis + 1 along -axis; a voxel whose fragments face both ways has all six
// (DYNGI_VCT_SEEN_BOTH_SIDES).
#define DYNGI_VCT_SEEN_BOTH_SIDES 63u

// The cone parameters every VCT pass that marches cones shares (vct_cone.glsl reads them by name).
#define DYNGI_VCT_CONE_PARAMS                                                        \
  vec4 volume;       /* xyz world origin, w voxel size */                          \
  float res;         /* voxels per side */                                         \
  float maxDistance; /* voxels a diffuse cone marches */                           \
  float aoDistance;  /* voxels over which occlusion counts towards AO */          \
  float coneOffset;  /* voxels off the surface a cone starts */                   \
  float coneStep;   /* step = this x the cone's diameter */                       \
  uint cones;        /* diffuse cones */                                           \
  float farNarrowing; /* footprints over 2^DYNGI_VCT_WHOLE_LEVELS_BELOW read 2^-this of theirs */
// A radiance update spread over frames: this frame updates part `part` of `parts` (vct_parts.glsl; 1: all)
// and whatever lies in the first `boxCount` changed boxes (where this frame's SVO build changed voxels).
#define DYNGI_VCT_PART_PUSH uint part; uint parts; uint boxCount;
#define DYNGI_VCT_INJECT_PUSH                                                        \
  vec4 volume;       /* xyz world origin, w voxel size */                          \
  uint lightCount;                                                                 \
  uint history;      /* 1: DIRECT holds last frame's radiance */                  \
  float temporalBlend;                                                             \
  float temporalResponse;                                                          \
  DYNGI_VCT_PART_PUSH                                                              \
  uint carried;      /* 1: level 0 is the direct radiance plus CARRIED */
#define DYNGI_VCT_EMITTER_PUSH                                                       \
  vec4 volume;       /* xyz world origin, w voxel size */                          \
  float res;         /* voxels per side */                                         \
  uint svoDepth;                                                                   \
  uint samples;      /* of the points, per voxel: a power of two up to DYNGI_VCT_EMITTER_MAX_SAMPLES */ \
  DYNGI_VCT_PART_PUSH
#define DYNGI_VCT_CLEAR_PUSH uint runCount; uint depth; /* the SVO's: its leaves are level-0 voxels, level depth - 1 the atlas' level-0 texels */ \
  uint atlasSlabWidth; /* texels; 0: isotropic, no atlas */
#define DYNGI_VCT_BOUNCE_PUSH DYNGI_VCT_CONE_PARAMS DYNGI_VCT_PART_PUSH /* the carried light's part and changed boxes this frame */
#define DYNGI_VCT_MIPS_PUSH uint destSlabWidth; /* texels; the isotropic chain has one slab */ uint sourceSlabWidth; /* 0: one source slab */ \
  uint nodeLevel; /* anisotropic: the SVO level whose cells are this atlas level's texels */ \
  uint leafShift; /* 3 x the SVO levels from this level's texels down to the leaves */ DYNGI_VCT_PART_PUSH
#define DYNGI_VCT_TRACE_PUSH DYNGI_VCT_CONE_PARAMS uint traceScale; uint specular; uint turnCones; /* 1: each traced pixel turns its cone set */ \
  float specularConeBelow; /* VctOptions::specularConeBelow: rougher pixels march no specular cone */ \
  uint traceFrames; /* 1, 2 or 4: the frames over which every traced pixel is traced once */ uint tracePhase; /* frame index mod traceFrames */ \
  uint coneInterleave; /* rows of traced pixels take turns over the cone set: each traces every this-many-th cone */ \
  uint coneRowShift; /* 1: pairs of rows take the turns (a frame tracing a quarter without history: its rows all even or all odd) */
#define DYNGI_VCT_REPROJECT_PUSH                                                     \
  mat4 previousViewProj;                                                           \
  uint traceScale;                                                                 \
  uint traceFrames;                                                                \
  uint tracePhase;                                                                 \
  uint history;      /* 0: nothing from last frame counts (first frame, light switched) */ \
  uint maxAge;       /* frames a reprojected value may go untraced before it is dropped */
#define DYNGI_VCT_UPSAMPLE_PUSH uint traceScale; float specularConeBelow; /* VctOptions::specularConeBelow */
// The roughness range under VctOptions::specularConeBelow over which the specular light blends from the
// cone's into the diffuse light's (vct_upsample.comp).
#define DYNGI_VCT_SPECULAR_BLEND 0.2
#define DYNGI_VCT_FILTER_PUSH uint traceScale; int radius; /* traced pixels */ int axisX; int axisY; /* (1, 0) or (0, 1) */
#define DYNGI_VCT_DEBUG_PUSH DYNGI_VCT_CONE_PARAMS uint mode; float mip;
#define DYNGI_VCT_PROBE_PUSH DYNGI_VCT_CONE_PARAMS uint count; float tanHalf;

// A point on an emitter, sampled by power (EmitterSet): Le / pdf(x) x |cos| G is its irradiance estimate.
#ifdef __cplusplus
struct alignas(16) VctEmitterPoint {
#else
struct VctEmitterPoint {
#endif
  vec4 position;  // xyz world, w the density per unit area it was drawn with (0: none)
  vec4 normal;    // xyz the triangle's unit normal (it emits from both sides)
  vec4 radiance;  // rgb Le
};

#ifdef __cplusplus
struct VctInjectPush { DYNGI_VCT_INJECT_PUSH };
struct VctEmitterPush { DYNGI_VCT_EMITTER_PUSH };
struct VctClearPush { DYNGI_VCT_CLEAR_PUSH };
struct VctBouncePush { DYNGI_VCT_BOUNCE_PUSH };
struct VctMipsPush { DYNGI_VCT_MIPS_PUSH };
struct VctTracePush { DYNGI_VCT_TRACE_PUSH };
struct VctReprojectPush { DYNGI_VCT_REPROJECT_PUSH };
struct VctUpsamplePush { DYNGI_VCT_UPSAMPLE_PUSH };
struct VctFilterPush { DYNGI_VCT_FILTER_PUSH };
struct VctDebugPush { DYNGI_VCT_DEBUG_PUSH };
struct VctProbePush { DYNGI_VCT_PROBE_PUSH };

static_assert(sizeof(VctInjectPush) == 48 && offsetof(VctInjectPush, temporalResponse) == 28 && offsetof(VctInjectPush, carried) == 44);
static_assert(sizeof(VctEmitterPush) == 40 && offsetof(VctEmitterPush, boxCount) == 36 && sizeof(VctEmitterPoint) == 48);
static_assert(sizeof(VctMipsPush) == 28 && offsetof(VctMipsPush, boxCount) == 24);
static_assert(sizeof(VctClearPush) == 12 && sizeof(VctUpsamplePush) == 8 && sizeof(VctFilterPush) == 16);
static_assert(sizeof(VctBouncePush) == 56 && offsetof(VctBouncePush, coneStep) == 32 && offsetof(VctBouncePush, boxCount) == 52);
static_assert(sizeof(VctTracePush) == 76 && offsetof(VctTracePush, traceScale) == 44 && offsetof(VctTracePush, coneInterleave) == 68);
static_assert(sizeof(VctReprojectPush) == 84 && offsetof(VctReprojectPush, traceScale) == 64 && offsetof(VctReprojectPush, maxAge) == 80);
static_assert(sizeof(VctDebugPush) == 52 && offsetof(VctDebugPush, mip) == 48);
static_assert(sizeof(VctProbePush) == 52 && offsetof(VctProbePush, tanHalf) == 48);
#endif

DYNGI_GPU_NAMESPACE_END

#endif
