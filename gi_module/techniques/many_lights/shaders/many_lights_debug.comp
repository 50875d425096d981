#version 460
// Debug views of the many-lights technique, written over the HDR image.
// mode 0: VPL positions as dots over the final image (white: lit directly, orange: second bounce, red:
// third); 1: the K x K sub-images side by side, each an estimate of the whole indirect light from its
// own VPL subset (times albedo).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "many_lights_shared.h"
layout(local_size_x = 64) in;
layout(set = 0, binding = DYNGI_MANY_LIGHTS_DEBUG_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_MANY_LIGHTS_DEBUG_BINDING_G_ALBEDO) uniform sampler2D gAlbedo;
layout(set = 0, binding = DYNGI_MANY_LIGHTS_DEBUG_BINDING_RAW, rgba32ui) uniform readonly uimage2D raw;  // filter_input.glsl's packing
layout(set = 0, binding = DYNGI_MANY_LIGHTS_DEBUG_BINDING_VPLS) readonly buffer Vpls { GpuVpl vpls[]; };
layout(set = 0, binding = DYNGI_MANY_LIGHTS_DEBUG_BINDING_HDR, rgba32f) uniform image2D hdr;
layout(push_constant) uniform Push { DYNGI_MANY_LIGHTS_DEBUG_PUSH };
#include "filter_input.glsl"
void main() {
  uint i = gl_GlobalInvocationID.x;
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (mode == 0u) {
    if (i >= vplCount) return;
    GpuVpl v = vpls[i];
    if (v.position.w < 0.0) return;
    vec4 clip = frame.viewProj * vec4(v.position.xyz, 1.0);
    if (clip.w <= 0.0) return;
    vec2 p = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size);
    vec3 c = v.position.w < 0.5 ? vec3(4.0) : (v.position.w < 1.5 ? vec3(4.0, 1.5, 0.0) : vec3(4.0, 0.0, 0.0));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec2 q = ivec2(p) + ivec2(dx, dy);
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) imageStore(hdr, q, vec4(c, 1.0));
      }
    return;
  }
  if (i >= uint(size.x * size.y)) return;
  ivec2 px = ivec2(i % uint(size.x), i / uint(size.x));
  // The gather's screen: the frame's, or the reduced one (VplOptions::gatherScale).
  ivec2 rawSize = imageSize(raw), at = px * rawSize / size;
  ivec2 tile = rawSize / int(K);
  ivec2 sub = min(at / max(tile, ivec2(1)), ivec2(int(K) - 1));
  ivec2 src = (at - sub * tile) * int(K) + sub;
  src = clamp(src, ivec2(0), rawSize - 1);
  // Each sub-image alone is a (noisier) estimate of the whole indirect light: shown at full scale.
  vec4 srcAlbedo = texelFetch(gAlbedo, clamp(src * size / rawSize, ivec2(0), size - 1), 0);
  imageStore(hdr, px, vec4(filterLight(imageLoad(raw, src)) * srcAlbedo.rgb * (1.0 - srcAlbedo.a), 1.0));
}
