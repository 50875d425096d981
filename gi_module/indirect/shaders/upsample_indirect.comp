#version 460
// A VPL technique's indirect light, gathered and filtered on the reduced screen (reduced_screen.h), to
// every pixel of targets.indirect: the 4 nearest reduced pixels, bilinear weights times how well each
// one's surface matches this pixel's (shared/surface_match.glsl), so light does not cross depth edges or
// corners. A pixel no reduced neighbour matches (a sliver thinner than the reduction) takes its
// best-matching one.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_LOW_POSITION, rgba32f) uniform readonly image2D lowPosition;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_LOW_NORMAL, rgba16f) uniform readonly image2D lowNormal;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_LOW_INDIRECT, rgba32f) uniform readonly image2D lowIndirect;
layout(set = 0, binding = DYNGI_UPSAMPLE_BINDING_OUT_INDIRECT, rgba32f) uniform writeonly image2D outIndirect;
layout(push_constant) uniform Push { DYNGI_REDUCED_SCREEN_PUSH };
#include "shared/surface_match.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {
    imageStore(outIndirect, px, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec3 n = normalize(imageLoad(gNormal, px).xyz);
  // Reduced pixel q's centre is the full-resolution point (q + 0.5) scale: this pixel's place among them.
  vec2 u = (vec2(px) + 0.5) / vec2(scaleX, scaleY) - 0.5;
  ivec2 q0 = ivec2(floor(u)), low = imageSize(lowIndirect);
  vec2 f = u - vec2(q0);
  // A plane distance of 1 percent of the view distance halves the weight.
  float planeScale = 0.01 * max(length(pos.xyz - frame.cameraPos.xyz), 1e-4);
  vec3 sum = vec3(0.0), best = vec3(0.0);
  float total = 0.0, bestMatch = -1.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = clamp(q0 + o, ivec2(0), low - 1);
    vec4 qp = imageLoad(lowPosition, q);
    float match = qp.w == 0.0 ? 0.0 : surfaceMatch(pos.xyz, n, qp.xyz, normalize(imageLoad(lowNormal, q).xyz), planeScale);
    vec3 light = imageLoad(lowIndirect, q).rgb;
    vec2 b = mix(1.0 - f, f, vec2(o));
    float w = b.x * b.y * match;
    sum += w * light;
    total += w;
    if (qp.w != 0.0 && match > bestMatch) bestMatch = match, best = light;
  }
  imageStore(outIndirect, px, vec4(total > 1e-4 ? sum / total : best, 1.0));
}
