#version 460
// The traced pixels (one per traceScale x traceScale block) to every pixel: the 4 nearest traced pixels,
// bilinear weights times how well each one's surface matches this pixel's (distance from this pixel's
// tangent plane, normal agreement), so light does not bleed across depth edges or corners. A pixel no
// traced neighbour matches takes its best-matching one. Values vct_reproject.comp marked missing (alpha < 0)
// are left out: with the trace spread over frames every 2 x 2 window still holds one traced this frame.
// Writes the lighting pass's inputs:
// targets.indirect (E / pi, AO in alpha) and targets.specular.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_G_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_G_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_LOW_DIFFUSE, rgba16f) uniform readonly image2D lowDiffuse;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_LOW_SPECULAR, rgba16f) uniform readonly image2D lowSpecular;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_LOW_SURFACE, rgba32ui) uniform readonly uimage2D lowSurface;  // vct_surface.glsl
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_OUT_DIFFUSE, rgba32f) uniform writeonly image2D outDiffuse;
layout(set = 0, binding = DYNGI_VCT_UPSAMPLE_BINDING_OUT_SPECULAR, rgba16f) uniform writeonly image2D outSpecular;
layout(push_constant) uniform Push { DYNGI_VCT_UPSAMPLE_PUSH };
#include "vct_surface.glsl"
#include "vct_surface_match.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 full = ivec2(frame.sizeAndCount.xy);
  if (any(greaterThanEqual(px, full))) return;
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {
    imageStore(outDiffuse, px, vec4(0.0, 0.0, 0.0, 1.0));
    imageStore(outSpecular, px, vec4(0.0));
    return;
  }
  vec3 n = normalize(imageLoad(gNormal, px).xyz);
  int s = int(traceScale), h = s / 2;
  ivec2 low = imageSize(lowDiffuse);
  // Traced pixel q sits at full-resolution pixel q s + h.
  vec2 t = vec2(px - h) / float(s);
  ivec2 q0 = ivec2(floor(t));
  vec2 f = t - vec2(q0);
  // A plane distance of 1 percent of the view distance halves the weight.
  float scale = 0.01 * max(length(pos.xyz - frame.cameraPos.xyz), 1e-4);
  vec4 diffuse = vec4(0.0), specular = vec4(0.0);
  float total = 0.0, best = -1.0, specularTotal = 0.0, bestSpecularMatch = -1.0;
  vec4 bestDiffuse = vec4(0.0, 0.0, 0.0, 1.0), bestSpecular = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = clamp(q0 + o, ivec2(0), low - 1);
    vec3 qp, qn;
    float match = vctUnpackSurface(imageLoad(lowSurface, q), qp, qn) ? vctSurfaceMatch(pos.xyz, n, qp, qn, scale) : 0.0;
    float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    vec4 d = imageLoad(lowDiffuse, q), sp = imageLoad(lowSpecular, q);
    float w = d.a < 0.0 ? 0.0 : bilinear * match, ws = sp.a < 0.0 ? 0.0 : bilinear * match;
    diffuse += w * d;
    specular += ws * sp;
    total += w;
    specularTotal += ws;
    if (d.a >= 0.0 && match > best) best = match, bestDiffuse = d;
    if (sp.a >= 0.0 && match > bestSpecularMatch) bestSpecularMatch = match, bestSpecular = sp;
  }
  diffuse = total > 1e-4 ? diffuse / total : bestDiffuse;
  specular = specularTotal > 1e-4 ? specular / specularTotal : bestSpecular;
  imageStore(outDiffuse, px, diffuse);
  imageStore(outSpecular, px, vec4(specular.rgb, 1.0));
}
