#version 460
// VCT debug views over the HDR image. `radiance` / `opacity`: each pixel's camera ray marched through the
// volume at one mip (front to back, as a cone of constant footprint 2^mip voxels), showing the radiance
// it gathers or its opacity as grey. `ao`, `specular`: the traced images as the lighting pass reads them
// (AO as grey, specular radiance).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "vct_shared.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool kAnisotropic = false;
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_RADIANCE) uniform sampler3D vctRadiance;
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_ANISO) uniform sampler3D vctAniso;
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_INDIRECT, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_SPECULAR, rgba16f) uniform readonly image2D specular;
layout(set = 0, binding = DYNGI_VCT_DEBUG_BINDING_OUT_HDR, rgba32f) uniform writeonly image2D outHdr;
layout(push_constant) uniform Push { DYNGI_VCT_DEBUG_PUSH };
#include "vct_cone.glsl"

// Where a ray enters the volume [0, res]^3 (t >= 0), or -1 when it misses it.
float entry(vec3 o, vec3 d) {
  vec3 inv = 1.0 / d;
  vec3 t0 = (vec3(0.0) - o) * inv, t1 = (vec3(res) - o) * inv;
  float tn = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z));
  float tf = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
  return tf < max(tn, 0.0) ? -1.0 : max(tn, 0.0);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec3 colour;
  if (mode <= 1u) {
    vec2 ndc = (vec2(px) + 0.5) / vec2(frame.sizeAndCount.xy) * 2.0 - 1.0;
    vec4 farP = frame.invViewProj * vec4(ndc, 1.0, 1.0);
    vec3 d = normalize(farP.xyz / farP.w - frame.cameraPos.xyz);
    vec3 o = (frame.cameraPos.xyz - volume.xyz) / volume.w;
    float t = entry(o, d);
    vec4 acc = vec4(0.0);
    if (t >= 0.0) {
      float footprint = exp2(mip);
      for (int i = 0; i < 4 * int(res) && acc.a < 0.99; ++i) {
        vec3 p = o + (t + 0.5 * footprint) * d;
        if (any(lessThan(p, vec3(-1e-3))) || any(greaterThan(p, vec3(res + 1e-3)))) break;
        vec4 part = vctSample(p, mip, d, 0.5, vec2(0.0, 1.0));  // half-footprint steps, the mip asked for
        acc += (1.0 - acc.a) * part;
        t += 0.5 * footprint;
      }
    }
    colour = mode == 0u ? acc.rgb : vec3(acc.a);
  } else if (mode == 2u) {
    colour = vec3(imageLoad(indirect, px).a);
  } else {
    colour = imageLoad(specular, px).rgb;
  }
  imageStore(outHdr, px, vec4(colour, 1.0));
}
