// The many-lights technique's C++/GLSL layouts: reflective shadow maps, VPL sampling and bounces, its
// debug views (gi_module/techniques/many_lights/).
#ifndef DYNGI_MANY_LIGHTS_SHARED_H
#define DYNGI_MANY_LIGHTS_SHARED_H

#include "indirect_shared.h"
#include "voxel_shared.h"

DYNGI_GPU_NAMESPACE_BEGIN

// One layer of the reflective shadow maps (storage buffer): how light `light` sees the scene.
#ifdef __cplusplus
struct alignas(16) RsmLayer {
#else
struct RsmLayer {
#endif
  mat4 viewProj;
  vec4 axis;            // xyz view forward, w texel footprint (perspective: per unit distance; ortho: world side)
  uint lightIndex;
  uint orthographic;    // 0/1
  uint resolution;      // RSM texels per side
  uint pad0;
};

// Push constants of the RSM draw (one layer; the casters' instances are the frame's DrawInstances).
#define DYNGI_RSM_PUSH uint layer; /* the RsmLayer drawn */

// many_lights_debug
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_FRAME 0
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_G_ALBEDO 1
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_RAW 3
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_VPLS 4
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_HDR 5
// rsm
#define DYNGI_RSM_BINDING_LAYERS 0
#define DYNGI_RSM_BINDING_LIGHTS 1
#define DYNGI_RSM_BINDING_BASE_COLOR_TEX 2
#define DYNGI_RSM_BINDING_METALLIC_ROUGHNESS_TEX 3
#define DYNGI_RSM_BINDING_NORMAL_TEX 4
#define DYNGI_RSM_BINDING_INSTANCES 5
// vpl_bounce
#define DYNGI_VPL_BOUNCE_BINDING_VPLS 0
#define DYNGI_VPL_BOUNCE_BINDING_NODES 1
#define DYNGI_VPL_BOUNCE_BINDING_NODE_CELLS 2
#define DYNGI_VPL_BOUNCE_BINDING_VOXEL_ATTRIBUTES 3
// vpl_tail
#define DYNGI_VPL_TAIL_BINDING_VPLS 0
// vpl_cdf_rows
#define DYNGI_VPL_CDF_ROWS_BINDING_RSM_FLUX 0
#define DYNGI_VPL_CDF_ROWS_BINDING_ROW_PREFIX 1
#define DYNGI_VPL_CDF_ROWS_BINDING_ROW_SUMS 2
// vpl_cdf_total
#define DYNGI_VPL_CDF_TOTAL_BINDING_ROW_SUMS 0
// vpl_sample
#define DYNGI_VPL_SAMPLE_BINDING_RSM_POSITION 0
#define DYNGI_VPL_SAMPLE_BINDING_RSM_NORMAL 1
#define DYNGI_VPL_SAMPLE_BINDING_RSM_FLUX 2
#define DYNGI_VPL_SAMPLE_BINDING_ROW_PREFIX 3
#define DYNGI_VPL_SAMPLE_BINDING_ROW_CDF 4
#define DYNGI_VPL_SAMPLE_BINDING_VPLS 5

#define DYNGI_MAX_RSM_LAYERS 24

#define DYNGI_VPL_CDF_ROWS_PUSH uint res; uint layers;
#define DYNGI_VPL_CDF_TOTAL_PUSH uint rows;
#define DYNGI_VPL_SAMPLE_PUSH uint res; uint layers; uint count; uint seed;
#define DYNGI_VPL_BOUNCE_PUSH                                                        \
  vec4 worldToVoxel; /* xyz origin, w 1 / voxel size */                            \
  uint parentFirst;  /* first VPL of bounce b-1 */                                 \
  uint count;        /* VPLs per bounce */                                         \
  uint bounce;                                                                     \
  uint depth;                                                                      \
  float res;                                                                       \
  float lift;        /* voxel units the ray starts off its surface */ \
  uint seed;         /* VplOptions::seed: turns every bounce's Halton points (Cranley-Patterson) */ \
  uint parentStride; /* one parent in each run of this many (the tail's probes, bounce_tail.h); else 1 */
#define DYNGI_VPL_TAIL_PUSH                                                          \
  uint lastFirst;    /* first VPL of the last gathered bounce; its probes follow it */ \
  uint count;        /* VPLs per bounce */ \
  uint probes;       /* the probes after them (one per run of VplOptions::bounceTailStride) */
#define DYNGI_MANY_LIGHTS_DEBUG_PUSH uint mode; uint K; uint vplCount;

#ifdef __cplusplus
struct VplCdfRowsPush { DYNGI_VPL_CDF_ROWS_PUSH };
struct VplCdfTotalPush { DYNGI_VPL_CDF_TOTAL_PUSH };
struct VplSamplePush { DYNGI_VPL_SAMPLE_PUSH };
struct VplBouncePush { DYNGI_VPL_BOUNCE_PUSH };
struct VplTailPush { DYNGI_VPL_TAIL_PUSH };
struct ManyLightsDebugPush { DYNGI_MANY_LIGHTS_DEBUG_PUSH };

static_assert(sizeof(RsmLayer) == 96 && offsetof(RsmLayer, axis) == 64 && offsetof(RsmLayer, lightIndex) == 80);
struct RsmPush { DYNGI_RSM_PUSH };
static_assert(sizeof(RsmPush) == 4);
static_assert(sizeof(VplCdfRowsPush) == 8 && sizeof(VplCdfTotalPush) == 4 && sizeof(VplSamplePush) == 16);
static_assert(sizeof(VplBouncePush) == 48 && offsetof(VplBouncePush, parentFirst) == 16 && offsetof(VplBouncePush, seed) == 40);
static_assert(sizeof(VplTailPush) == 12 && sizeof(ManyLightsDebugPush) == 12);
#endif

DYNGI_GPU_NAMESPACE_END

#endif
