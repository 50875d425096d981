#version 460
// The `indirect` view every technique has: the GI's indirect diffuse light before albedo (E / pi, what
// the lighting pass multiplies by the diffuse albedo) written over the HDR image.
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_GI_VIEW_BINDING_INDIRECT, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = DYNGI_GI_VIEW_BINDING_OUT_HDR, rgba32f) uniform writeonly image2D outHdr;
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, imageSize(outHdr)))) return;
  imageStore(outHdr, px, vec4(imageLoad(indirect, px).rgb, 1.0));
}
