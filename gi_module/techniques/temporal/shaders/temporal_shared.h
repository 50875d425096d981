// The temporal technique's C++/GLSL layouts: its gather variant's bindings, the temporal sets' cameras,
// the accumulation and the reprojection queue (gi_module/techniques/temporal/).
#ifndef DYNGI_TEMPORAL_SHARED_H
#define DYNGI_TEMPORAL_SHARED_H

#include "indirect_shared.h"

DYNGI_GPU_NAMESPACE_BEGIN

// temporal_reproject
#define DYNGI_TEMPORAL_REPROJECT_BINDING_FRAME 0
#define DYNGI_TEMPORAL_REPROJECT_BINDING_SET_SAMPLES 1
#define DYNGI_TEMPORAL_REPROJECT_BINDING_CAMERAS 2
#define DYNGI_TEMPORAL_REPROJECT_BINDING_SUMS 3
#define DYNGI_TEMPORAL_REPROJECT_BINDING_FILTER_INPUT 4
#define DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE 5
#define DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE_ARGS 6

#define DYNGI_TEMPORAL_GATHER_BINDING_SET_SAMPLES (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 0)
#define DYNGI_TEMPORAL_GATHER_BINDING_SUMS (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 1)
#define DYNGI_TEMPORAL_GATHER_BINDING_QUEUE (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 2)
#define DYNGI_TEMPORAL_GATHER_BINDING_QUEUE_ARGS (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 3)

// Temporal sets at most (set counts in bit masks; the set cameras are a uniform array of this size).
#define DYNGI_MAX_TEMPORAL_SETS 32

// The camera a temporal set's indirect buffer was gathered from (uniform array, one per set): enough to
// project a point into it and to rebuild the point a stored pixel's view depth stands for (the pixel rays
// of engine FrameUniforms).
#ifdef __cplusplus
struct alignas(16) TemporalSetCamera {
#else
struct TemporalSetCamera {
#endif
  mat4 viewProj;
  vec4 position;        // xyz camera position
  vec4 pixelRay0;       // xyz ray through pixel (0, 0)'s centre at unit view depth
  vec4 pixelRayStepX;   // xyz per pixel to the right
  vec4 pixelRayStepY;   // xyz per pixel down
};

// Temporal accumulation settings (push constants).
#ifdef __cplusplus
struct alignas(16) AccumulatePush {
#else
struct AccumulatePush {
#endif
  uint setCount;        // T
  uint currentSet;      // the set gathered this frame
  uint storedSets;      // bits: sets stored at least once
  uint setsFromThisCamera;  // bits: sets stored from the current camera
  // 1: incremental (camera as last frame, currentSet last stored from it, sums current; the gather
  // queues the pixels the reprojection takes); 0: the reprojection takes every pixel.
  uint incremental;
  uint currentSetWasStored;  // 1: currentSet held a sample before this frame
  uint pad0, pad1;
  float reprojectionCutoff;  // relative to the view distance
  float pad2, pad3, pad4;
};

// The pixels the gather queues for the full reprojection (storage buffer, reset every frame); its first
// three words are the reprojection pass's indirect dispatch (VkDispatchIndirectCommand).
#ifdef __cplusplus
struct alignas(16) TemporalQueue {
#else
struct TemporalQueue {
#endif
  uvec4 dispatchAndCount;  // x workgroups of 64 (raised by the thread that queues every 64th pixel), y 1, z 1,
                           // w pixels queued
};

#ifdef __cplusplus

static_assert(sizeof(TemporalSetCamera) == 128 && offsetof(TemporalSetCamera, position) == 64 &&
              offsetof(TemporalSetCamera, pixelRayStepY) == 112);
static_assert(sizeof(AccumulatePush) == 48 && offsetof(AccumulatePush, incremental) == 16 &&
              offsetof(AccumulatePush, reprojectionCutoff) == 32);
// The temporal gather's push constants (GatherPush, then AccumulatePush): Vulkan guarantees 128 bytes.
static_assert(sizeof(GatherPush) + sizeof(AccumulatePush) <= 128);
static_assert(sizeof(TemporalQueue) == 16);
#endif

DYNGI_GPU_NAMESPACE_END

#endif
