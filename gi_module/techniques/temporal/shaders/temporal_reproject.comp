#version 460
// The temporal technique's full reprojection (temporal_accumulate.glsl's temporalAccumulateFull) for the
// pixels the gather could not update incrementally: the queued ones (mode.x = 1, dispatched indirectly
// from the queue's count), or every pixel when the camera moved (mode.x = 0, one thread per pixel in
// row order). Overwrites those pixels' filter input.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "temporal_shared.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_SET_SAMPLES, rg32ui) uniform uimage2DArray setSamples;
// A uniform buffer: every lane reads the same set's camera, which lavapipe then loads once per lane
// group instead of lane by lane (as a storage buffer).
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_CAMERAS) uniform Cameras { TemporalSetCamera cameras[DYNGI_MAX_TEMPORAL_SETS]; };
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_SUMS, rgba32f) uniform image2D sums;
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_FILTER_INPUT, rgba32ui) uniform uimage2D filterInput;  // filter_input.glsl's packing
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE) readonly buffer Queue { uint queuedPixels[]; };  // x | y << 16
layout(set = 0, binding = DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE_ARGS) readonly buffer QueueArgs { TemporalQueue queue; };
layout(push_constant) uniform Push { AccumulatePush acc; };
#define DYNGI_TEMPORAL_REPROJECT
#include "filter_input.glsl"
#include "temporal_accumulate.glsl"

void main() {
  uint id = gl_GlobalInvocationID.x, width = frame.sizeAndCount.x;
  ivec2 px;
  if (acc.incremental != 0u) {
    if (id >= queue.dispatchAndCount.w) return;
    uint packedPx = queuedPixels[id];
    px = ivec2(packedPx & 0xffffu, packedPx >> 16);
  } else {
    px = ivec2(id % width, id / width);
  }
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  if (setSample(px, acc.currentSet).a <= 0.0) return;  // no surface: the gather wrote it
  uvec4 stored = imageLoad(filterInput, px);
  imageStore(filterInput, px, temporalAccumulateFull(px, filterPackedNormal(stored)));
}
