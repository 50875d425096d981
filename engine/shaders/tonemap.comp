#version 460
// Exposure, tone mapping and sRGB encoding into the 8-bit display image.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_TONEMAP_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_TONEMAP_BINDING_HDR, rgba32f) uniform readonly image2D hdr;
layout(set = 0, binding = DYNGI_TONEMAP_BINDING_LDR, rgba8) uniform writeonly image2D ldr;

// Narkowicz's fit of the ACES filmic curve.
vec3 acesFit(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 srgbEncode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec3 c = imageLoad(hdr, px).rgb * frame.exposure.x;
  if (any(isnan(c)) || any(isinf(c))) c = vec3(1.0, 0.0, 1.0);  // make bad values visible, never silent
  // The curve is flat at 1 long before 1e4; clamped first, its squares cannot overflow to inf / inf.
  c = clamp(c, 0.0, 1e4);
  c = frame.exposure.y < 0.5 ? acesFit(c) : clamp(c, 0.0, 1.0);
  imageStore(ldr, px, vec4(srgbEncode(c), 1.0));
}
