#version 460
// The merge filter's first pass (filter_tent.glsl): along rows, into the packed intermediate the second
// pass (filter_columns.comp) reads, with the pixel's own depth and normal.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint K = 4u;
layout(set = 0, binding = DYNGI_FILTER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_FILTER_BINDING_FILTER_INPUT, rgba32ui) uniform readonly uimage2D filterInput;
layout(set = 0, binding = DYNGI_FILTER_BINDING_OUT_ROWS, rgba32ui) uniform writeonly uimage2D outRows;
layout(push_constant) uniform Push { DYNGI_INDIRECT_FILTER_PUSH };
#include "filter_tent.glsl"
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  uvec4 centre;
  vec3 light;
  bool surface = tentFilter(px, ivec2(1, 0), centre, light);
  imageStore(outRows, px, surface ? packFilterInput(filterViewDepth(centre), filterPackedNormal(centre), light) : uvec4(0u));
}
