#version 460
// The G-buffer at 1/scale of the resolution for a VPL technique's screen passes (reduced_screen.h):
// reduced pixel q takes the full-resolution pixel under its centre, (q + 0.5) scale, as it is, no
// average, so each one is a real surface point within half a pixel of the ray the reduced frame's
// uniforms give it.
#extension GL_GOOGLE_include_directive : require
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_ALBEDO, rgba8) uniform readonly image2D gAlbedo;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_EMISSIVE, rgba16f) uniform readonly image2D gEmissive;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_OUT_POSITION, rgba32f) uniform writeonly image2D outPosition;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_OUT_NORMAL, rgba16f) uniform writeonly image2D outNormal;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_OUT_ALBEDO, rgba8) uniform writeonly image2D outAlbedo;
layout(set = 0, binding = DYNGI_REDUCE_BINDING_OUT_EMISSIVE, rgba16f) uniform writeonly image2D outEmissive;
layout(push_constant) uniform Push { DYNGI_REDUCED_SCREEN_PUSH };

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(outPosition)))) return;
  ivec2 px = min(ivec2((vec2(q) + 0.5) * vec2(scaleX, scaleY)), imageSize(gPosition) - 1);
  imageStore(outPosition, q, imageLoad(gPosition, px));
  imageStore(outNormal, q, imageLoad(gNormal, px));
  imageStore(outAlbedo, q, imageLoad(gAlbedo, px));
  imageStore(outEmissive, q, imageLoad(gEmissive, px));
}
