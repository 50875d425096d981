#version 460
// The merge filter's second pass (filter_tent.glsl): along columns of the rows pass's result, into
// targets.indirect; with kCompensate, plus the clamp compensation (compensate.comp) brought to full
// resolution: bilinear over the 2 x 2 texels around the pixel, each kept only if it lies on the pixel's
// surface (the tent's test); where none does (a sliver) nothing is added.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "indirect_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint K = 4u;
layout(constant_id = 1) const bool kCompensate = false;
layout(set = 0, binding = DYNGI_FILTER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_FILTER_BINDING_FILTER_INPUT, rgba32ui) uniform readonly uimage2D filterInput;
layout(set = 0, binding = DYNGI_FILTER_BINDING_OUT_INDIRECT, rgba32f) uniform writeonly image2D outIndirect;
layout(set = 0, binding = DYNGI_FILTER_BINDING_COMPENSATION, rgba32ui) uniform readonly uimage2D compensation;
layout(push_constant) uniform Push { DYNGI_INDIRECT_FILTER_PUSH };
#include "filter_tent.glsl"
#include "compensate.glsl"

// The compensation at pixel px, whose surface is at view depth t with normal n.
vec3 compensationAt(ivec2 px, float t, vec3 n) {
  vec3 x = frame.cameraPos.xyz + t * pixelRay(px);
  float scale = planeTolerance * t * length(pixelRay(px));
  // Texel q sits at pixel q S + S / 2: the pixel's place among the texels.
  vec2 u = (vec2(px) - float(DYNGI_COMPENSATE_SCALE / 2)) / float(DYNGI_COMPENSATE_SCALE);
  ivec2 first = ivec2(floor(u)), low = compensationSize();
  vec2 f = u - vec2(first);
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int j = 0; j < 4; ++j) {
    ivec2 o = ivec2(j & 1, j >> 1);
    ivec2 q = clamp(first + o, ivec2(0), low - 1);
    uvec4 tap = imageLoad(compensation, q);
    float tq = filterViewDepth(tap);
    vec3 pq = frame.cameraPos.xyz + tq * pixelRay(tracedPixel(q));
    bool same = tq > 0.0 && dot(n, filterNormal(tap)) >= 0.9 && abs(dot(pq - x, n)) <= scale;
    vec2 b = mix(1.0 - f, f, vec2(o));
    float w = same ? b.x * b.y + 1e-4 : 0.0;  // + 1e-4: a texel on the surface counts at a bilinear weight of 0
    sum += w * filterLight(tap);
    wsum += w;
  }
  return wsum > 0.0 ? sum / wsum : vec3(0.0);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  uvec4 centre;
  vec3 light;
  bool surface = tentFilter(px, ivec2(0, 1), centre, light);
  if (kCompensate && surface) light += compensationAt(px, filterViewDepth(centre), normalize(filterNormal(centre)));
  imageStore(outIndirect, px, vec4(light, 1.0));
}
