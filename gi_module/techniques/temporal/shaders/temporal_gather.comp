#version 460
// The temporal technique's gather: the shared gather (gather.glsl), whose light goes into the temporal
// sets and running sums right away (temporal_accumulate.glsl), with no image in between. What is written
// is the accumulated light, or, for pixels queued for the full reprojection, this set's light until
// temporal_reproject.comp overwrites it.
#extension GL_GOOGLE_include_directive : require
#include "temporal_shared.h"
#define GATHER_EXTRA_PUSH AccumulatePush acc;
#include "gather.glsl"
layout(set = 0, binding = DYNGI_TEMPORAL_GATHER_BINDING_SET_SAMPLES, rg32ui) uniform uimage2DArray setSamples;
layout(set = 0, binding = DYNGI_TEMPORAL_GATHER_BINDING_SUMS, rgba32f) uniform image2D sums;
layout(set = 0, binding = DYNGI_TEMPORAL_GATHER_BINDING_QUEUE) writeonly buffer Queue { uint queuedPixels[]; };  // x | y << 16
layout(set = 0, binding = DYNGI_TEMPORAL_GATHER_BINDING_QUEUE_ARGS) buffer QueueArgs { TemporalQueue queue; };
#include "temporal_accumulate.glsl"

void main() {
  ivec2 px;
  vec3 light;
  float depth;
  uvec2 packedNormal;
  if (!gatherPixel(px, light, depth, packedNormal)) return;
  uvec4 result = depth > 0.0 ? packFilterInput(depth, packedNormal, light) : uvec4(0u);
  if (kGatherChunked && pc.chunkEnd < pc.vplCount) {  // a part of the set: the last chunk accumulates the sum
    imageStore(outRaw, px, result);
    return;
  }
  uvec4 accumulated;
  if (temporalAccumulateIncremental(px, light, depth, packedNormal, accumulated)) result = accumulated;
  else if (acc.incremental != 0u) {
    // Queue the pixel for the full reprojection (temporal_reproject.comp); without a queue that pass
    // runs over every pixel.
    uint slot = atomicAdd(queue.dispatchAndCount.w, 1u);
    queuedPixels[slot] = uint(px.x) | (uint(px.y) << 16);
    if (slot % 64u == 0u) atomicAdd(queue.dispatchAndCount.x, 1u);
  }
  imageStore(outRaw, px, result);
}
