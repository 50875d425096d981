#version 460
// The merge filter's second pass (filter_tent.glsl): along columns of the rows pass's result, into
// targets.indirect.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint K = 4u;
layout(set = 0, binding = DYNGI_FILTER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_FILTER_BINDING_FILTER_INPUT, rgba32ui) uniform readonly uimage2D filterInput;
layout(set = 0, binding = DYNGI_FILTER_BINDING_OUT_INDIRECT, rgba32f) uniform writeonly image2D outIndirect;
layout(push_constant) uniform Push { DYNGI_INDIRECT_FILTER_PUSH };
#include "filter_tent.glsl"
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  uvec4 centre;
  vec3 light;
  tentFilter(px, ivec2(0, 1), centre, light);
  imageStore(outIndirect, px, vec4(light, 1.0));
}
