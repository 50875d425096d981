#version 460
// The temporal technique's full reprojection (temporal_accumulate.glsl's temporalAccumulateFull) for the
// pixels the gather could not update incrementally: the queued ones (grid.y = 1, dispatched indirectly
// from the queue's count), or every pixel when the camera moved (grid.y = 0, one thread per pixel in
// the per-pixel buffers' sub-image-major order). Overwrites those pixels' filter input.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) buffer SetSamples { uvec2 setSamples[]; };
// A uniform buffer: every lane reads the same set's camera, which lavapipe then loads once per lane
// group instead of lane by lane (as a storage buffer).
layout(set = 0, binding = 2) uniform Cameras { TemporalSetCamera cameras[DYNGI_MAX_TEMPORAL_SETS]; };
layout(set = 0, binding = 3) buffer Sums { vec4 sums[]; };
layout(set = 0, binding = 4, rgba32ui) uniform uimage2D filterInput;  // filter_input.glsl's packing
layout(set = 0, binding = 5) readonly buffer Queue { uint queuedPixels[]; };  // x | y << 16
layout(set = 0, binding = 6) readonly buffer QueueArgs { TemporalQueue queue; };
layout(push_constant) uniform Push { AccumulatePush acc; };
#define DYNGI_TEMPORAL_REPROJECT
#include "filter_input.glsl"
#include "temporal_accumulate.glsl"

void main() {
  const uint K = acc.grid.x;
  uint id = gl_GlobalInvocationID.x;
  ivec2 px;
  if (acc.grid.y != 0u) {
    if (id >= queue.dispatchAndCount.w) return;
    uint packedPx = queuedPixels[id];
    px = ivec2(packedPx & 0xffffu, packedPx >> 16);
  } else {
    // Inverse of temporalIndex.
    uvec2 subSize = acc.mode.zw;
    uint perSub = subSize.x * subSize.y;
    uint s = id / perSub, r = id % perSub;
    if (s >= K * K) return;
    px = ivec2(uvec2(r % subSize.x, r / subSize.x) * K + uvec2(s % K, s / K));
  }
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  if (uintBitsToFloat(setSamples[acc.sets.y * temporalLayerSize(K) + temporalIndex(px, K)].y) <= 0.0) return;  // no surface: the gather wrote it
  uvec4 stored = imageLoad(filterInput, px);
  imageStore(filterInput, px, temporalAccumulateFull(px, K, stored.y));
}
