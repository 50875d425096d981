#version 460
// The traced pixels (one per traceScale x traceScale block) to every pixel: the 4 nearest traced pixels,
// bilinear weights times how well each one's surface matches this pixel's (distance from this pixel's
// tangent plane, normal agreement), so light does not bleed across depth edges or corners. A pixel no
// traced neighbour matches takes its best-matching one. Values vct_reproject.comp marked missing (alpha < 0)
// are left out: with the trace spread over frames every 2 x 2 window still holds one traced this frame.
// Writes the lighting pass's inputs:
// targets.indirect (E / pi, AO in alpha) and targets.specular (rough pixels': the diffuse light, blended
// in under VctOptions::specularConeBelow).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
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
// False when every pixel's specular light is its diffuse light (no draw smoother than
// specularConeBelow): the lighting reads it from targets.indirect (SpecularSource::Indirect), and the
// specular image is neither filled nor written.
layout(constant_id = 0) const bool kSpecular = true;
#include "vct_surface.glsl"
#include "shared/surface_match.glsl"

// One invocation per block of traceScale x traceScale pixels that share their 4 nearest traced pixels:
// those are read once for the block (a pixel's own reads were 14 loads, 12 of them its neighbours').
void main() {
  ivec2 full = ivec2(frame.sizeAndCount.xy);
  int s = int(traceScale), h = s / 2;
  ivec2 low = imageSize(lowDiffuse);
  // Traced pixel q sits at full-resolution pixel q s + h: the block of q0 (its top-left neighbour, -1 left
  // of and above the first traced pixel) holds the pixels q0 s + h .. q0 s + h + s - 1.
  ivec2 q0 = ivec2(gl_GlobalInvocationID.xy) - 1;
  ivec2 first = q0 * s + h;
  if (any(greaterThanEqual(first, full)) || any(lessThan(first + s, ivec2(0)))) return;
  vec3 qp[4], qn[4];
  bool seen[4];
  vec4 d[4], sp[4];
  for (int i = 0; i < 4; ++i) {
    ivec2 q = clamp(q0 + ivec2(i & 1, i >> 1), ivec2(0), low - 1);
    seen[i] = vctUnpackSurface(imageLoad(lowSurface, q), qp[i], qn[i]);
    d[i] = imageLoad(lowDiffuse, q);
    sp[i] = imageLoad(lowSpecular, q);
  }
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      ivec2 px = first + ivec2(x, y);
      if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, full))) continue;
      vec4 pos = imageLoad(gPosition, px);
      if (pos.w == 0.0) {
        imageStore(outDiffuse, px, vec4(0.0, 0.0, 0.0, 1.0));
        if (kSpecular) imageStore(outSpecular, px, vec4(0.0));
        continue;
      }
      vec4 nr = imageLoad(gNormal, px);
      vec3 n = normalize(nr.xyz);
      vec2 t = vec2(px - h) / float(s);
      vec2 f = t - vec2(q0);
      // A plane distance of 1 percent of the view distance halves the weight.
      float scale = 0.01 * max(length(pos.xyz - frame.cameraPos.xyz), 1e-4);
      vec4 diffuse = vec4(0.0), specular = vec4(0.0);
      float total = 0.0, best = -1.0, specularTotal = 0.0, bestSpecularMatch = -1.0;
      vec4 bestDiffuse = vec4(0.0, 0.0, 0.0, 1.0), bestSpecular = vec4(0.0);
      for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        float match = seen[i] ? surfaceMatch(pos.xyz, n, qp[i], qn[i], scale) : 0.0;
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float w = d[i].a < 0.0 ? 0.0 : bilinear * match, ws = sp[i].a < 0.0 ? 0.0 : bilinear * match;
        diffuse += w * d[i];
        specular += ws * sp[i];
        total += w;
        specularTotal += ws;
        if (d[i].a >= 0.0 && match > best) best = match, bestDiffuse = d[i];
        if (sp[i].a >= 0.0 && match > bestSpecularMatch) bestSpecularMatch = match, bestSpecular = sp[i];
      }
      diffuse = total > 1e-4 ? diffuse / total : bestDiffuse;
      imageStore(outDiffuse, px, diffuse);
      if (!kSpecular) continue;
      specular = specularTotal > 1e-4 ? specular / specularTotal : bestSpecular;
      // Rough pixels' specular light is the diffuse light's (VctOptions::specularConeBelow).
      specular.rgb = mix(specular.rgb, diffuse.rgb, smoothstep(specularConeBelow - DYNGI_VCT_SPECULAR_BLEND, specularConeBelow, nr.w));
      imageStore(outSpecular, px, vec4(specular.rgb, 1.0));
    }
}
