// The C++/GLSL layouts of what both VPL techniques share (gi_module/indirect/): the VPL, the gather's
// bindings and settings, the geometry-aware filter and the clamp compensation.
#ifndef DYNGI_INDIRECT_SHARED_H
#define DYNGI_INDIRECT_SHARED_H

#include "shared/gi_gpu_types.h"

DYNGI_GPU_NAMESPACE_BEGIN

// A virtual point light: a point on a surface that reflects `flux` (watts, reflected: rho * E * A)
// with a cosine lobe around `normal`.
#ifdef __cplusplus
struct alignas(16) GpuVpl {
#else
struct GpuVpl {
#endif
  vec4 position;        // xyz world, w bounce (0: lit directly by a light), negative: invalid
  vec4 normal;          // xyz unit normal, w path index
  vec4 flux;            // rgb reflected flux, w luminance (for skipping dim VPLs)
};

// filter
#define DYNGI_FILTER_BINDING_FRAME 0
#define DYNGI_FILTER_BINDING_FILTER_INPUT 1
#define DYNGI_FILTER_BINDING_OUT_INDIRECT 2  // filter_columns
#define DYNGI_FILTER_BINDING_OUT_ROWS 3      // filter_rows: the packed intermediate
// compensate (the distance clamp's lost light: compensate.comp traces it between the merge filter's
// passes, filter_columns.comp adds it)
#define DYNGI_COMPENSATE_BINDING_FRAME 0
#define DYNGI_COMPENSATE_BINDING_POSITION 1
#define DYNGI_COMPENSATE_BINDING_NORMAL 2
#define DYNGI_COMPENSATE_BINDING_ALBEDO 3
#define DYNGI_COMPENSATE_BINDING_EMISSIVE 4
#define DYNGI_COMPENSATE_BINDING_ROWS 5             // the merge filter's rows pass: the indirect light where a ray lands
#define DYNGI_COMPENSATE_BINDING_LIGHTS 6
#define DYNGI_COMPENSATE_BINDING_SHADOW_MATRICES 7
#define DYNGI_COMPENSATE_BINDING_SHADOW_MAPS 8
#define DYNGI_COMPENSATE_BINDING_OUT 9              // one texel per DYNGI_COMPENSATE_SCALE^2 pixels, packed as filter_input.glsl
#define DYNGI_COMPENSATE_BINDING_TRACED 10          // compensate_blur: compensate.comp's output
#define DYNGI_FILTER_BINDING_COMPENSATION 4         // filter_columns: that image, read
#define DYNGI_COMPENSATE_SCALE 4                    // the compensation is traced for one pixel in 4 x 4

// The reduced screen (reduced_screen.h): the G-buffer at 1/s of the resolution for the gather and the
// filter (reduce_gbuffer.comp), and their light back to every pixel (upsample_indirect.comp).
#define DYNGI_REDUCE_BINDING_POSITION 0
#define DYNGI_REDUCE_BINDING_NORMAL 1
#define DYNGI_REDUCE_BINDING_ALBEDO 2
#define DYNGI_REDUCE_BINDING_EMISSIVE 3
#define DYNGI_REDUCE_BINDING_OUT_POSITION 4
#define DYNGI_REDUCE_BINDING_OUT_NORMAL 5
#define DYNGI_REDUCE_BINDING_OUT_ALBEDO 6
#define DYNGI_REDUCE_BINDING_OUT_EMISSIVE 7
#define DYNGI_UPSAMPLE_BINDING_FRAME 0
#define DYNGI_UPSAMPLE_BINDING_POSITION 1
#define DYNGI_UPSAMPLE_BINDING_NORMAL 2
#define DYNGI_UPSAMPLE_BINDING_LOW_POSITION 3
#define DYNGI_UPSAMPLE_BINDING_LOW_NORMAL 4
#define DYNGI_UPSAMPLE_BINDING_LOW_INDIRECT 5
#define DYNGI_UPSAMPLE_BINDING_OUT_INDIRECT 6
// Full-resolution pixels per reduced pixel along x and y (the full size over the reduced size): reduced
// pixel q's centre is the full-resolution point (q + 0.5) scale, and it samples the pixel there.
#define DYNGI_REDUCED_SCREEN_PUSH float scaleX; float scaleY;

// Bindings of the shared indirect gather (gather.glsl); a technique's gather variant adds its own after
// them (temporal_gather.comp).
#define DYNGI_GATHER_BINDING_FRAME 0
#define DYNGI_GATHER_BINDING_POSITION 1
#define DYNGI_GATHER_BINDING_NORMAL 2
#define DYNGI_GATHER_BINDING_VPLS 3
#define DYNGI_GATHER_BINDING_SVO_NODES 4
#define DYNGI_GATHER_BINDING_OUTPUT 5
#define DYNGI_GATHER_BINDING_VISIBILITY_BITS 6
#define DYNGI_GATHER_BINDING_CLAMP_SPREAD 7  // the clamp spread's table (shared/clamp_spread.h)
#define DYNGI_GATHER_FIRST_TECHNIQUE_BINDING 8


// GatherPush::visibility: how the gather decides whether a VPL sees a pixel.
#define DYNGI_VISIBILITY_SVO 0u   // march the SVO (nodes buffer)
#define DYNGI_VISIBILITY_NONE 1u  // V = 1
#define DYNGI_VISIBILITY_BITS 2u  // precomputed bits (Embree on the CPU)

// The bounce tail's probes stand for every bounce after the last, a smooth light; one landing by a
// corner would light the next surface as a point (a bright blob under the ceiling) where the later
// bounces light it evenly. Their clamp is this many times B: the blob's reach doubles and its peak is a
// quarter, the light it drops given back by the clamp spread as any VPL's.
#define DYNGI_TAIL_CLAMP_SCALE 4.0

// Settings of the indirect gather (push constants).
#ifdef __cplusplus
struct alignas(16) GatherPush {
#else
struct GatherPush {
#endif
  vec4 worldToVoxel;    // xyz origin, w 1 / voxel size
  float distanceClamp;  // B (world units^2): G = cos cos / max(B, d^2)
  float luminanceThreshold;  // relative to the first VPL's luminance
  float liftVoxels;     // SVO visibility: segment ends leave their surface by this many voxels
  float voxelResolution;
  uint vplCount;        // VPLs gathered (this set's)
  uint interleave;      // K
  uint visibility;      // DYNGI_VISIBILITY_*
  uint svoDepth;
  uint firstVpl;        // offset into the VPL buffer
  uint bitsPerPixel;    // DYNGI_VISIBILITY_BITS: visibility bits per pixel
  // The VPLs whose summed light the gathered ones estimate: vplCount, or a temporal set's size when
  // a GI budget gathers an evenly spread subset of it (each sub-image's sum is scaled by this over the
  // VPLs it gathered, so every sub-image is an unbiased estimate of the whole).
  uint estimatedCount;
  uint firstBit;        // DYNGI_VISIBILITY_BITS: where this gather's block of bits starts (one block a set)
  // The VPLs [chunkBegin, chunkEnd) of this dispatch (IndirectGatherPass::record splits a gather that
  // would give a pixel more than DYNGI_GATHER_MAX_VPLS_PER_PIXEL); chunkBegin is a multiple of K^2, and a
  // dispatch after the first adds the light the earlier ones left in the output.
  uint chunkBegin;
  uint chunkEnd;
  float clampSpread;    // the light the clamp drops is spread back, stretched this much along corners (shared/clamp_spread.h); 0: off
  // VPLs of this bounce and later (the bounce tail's probes) are gathered with the clamp times
  // DYNGI_TAIL_CLAMP_SCALE; 0: none.
  uint tailBounce;
};

// VPLs one gather dispatch gives a pixel at most. lavapipe counts every loop iteration of a shader
// invocation against one shared limit (65535, gallivm's loop limiter) and past it runs every loop once:
// a pixel gathering ~1000 VPLs (each an SVO march of a few hundred descent and step iterations) stopped
// part way, and whole workgroups came out dark. 64 leaves each VPL 1024 iterations.
#define DYNGI_GATHER_MAX_VPLS_PER_PIXEL 64u

#define DYNGI_INDIRECT_FILTER_PUSH float planeTolerance;
#define DYNGI_COMPENSATE_PUSH                                                        \
  float distanceClamp;   /* B: the gather's G = cos cos / max(B, d^2) */            \
  uint rays;             /* per traced texel */                                     \
  uint includeIndirect;  /* 1: the VPLs carry light that bounced before (bounces > 1 or the tail) */ \
  uint lightCount;                                                              \
  float planeTolerance;  /* blur: taps within this fraction of the view distance off the texel's plane */

#ifdef __cplusplus
struct IndirectFilterPush { DYNGI_INDIRECT_FILTER_PUSH };
struct CompensatePush { DYNGI_COMPENSATE_PUSH };
struct ReducedScreenPush { DYNGI_REDUCED_SCREEN_PUSH };

static_assert(sizeof(GpuVpl) == 48 && offsetof(GpuVpl, normal) == 16 && offsetof(GpuVpl, flux) == 32);
static_assert(sizeof(GatherPush) == 80 && offsetof(GatherPush, distanceClamp) == 16 && offsetof(GatherPush, vplCount) == 32 &&
              offsetof(GatherPush, firstVpl) == 48 && offsetof(GatherPush, chunkBegin) == 64 && offsetof(GatherPush, clampSpread) == 72);
static_assert(sizeof(IndirectFilterPush) == 4);
static_assert(sizeof(ReducedScreenPush) == 8);
static_assert(sizeof(CompensatePush) == 20 && offsetof(CompensatePush, planeTolerance) == 16);
#endif

DYNGI_GPU_NAMESPACE_END

#endif
