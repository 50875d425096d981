#version 460
// Temporal accumulation: every set's stored indirect light is reprojected into the current view.
// A stored sample counts only when the surface it was gathered for lies within `cutoff` (relative to
// the view distance) of the current pixel's surface; sets that miss (disocclusion) are made up for by
// scaling the found ones by T / found, so a pixel is never left black while any set sees it.
// Sets stored from the current camera (bit in sameCamera) skip the projection (same pixel); the
// surface test still runs, so objects that moved under a still camera are caught.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gPosition;
layout(set = 0, binding = 2) readonly buffer SetIndirect { vec4 setIndirect[]; };
layout(set = 0, binding = 3) readonly buffer SetDepth { float setDepth[]; };
struct SetCamera { mat4 viewProj; mat4 invViewProj; };
layout(set = 0, binding = 4) readonly buffer Cameras { SetCamera cameras[]; };
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D outAccumulated;
layout(push_constant) uniform Push { uint sets; uint validMask; float cutoff; uint sameCamera; };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { imageStore(outAccumulated, px, vec4(0.0)); return; }
  float tolerance = cutoff * max(length(p.xyz - frame.cameraPos.xyz), 1e-3);
  uint layer = uint(size.x * size.y);
  vec4 clipNow = frame.viewProj * vec4(p.xyz, 1.0);
  float depthNow = clipNow.z / clipNow.w;
  vec3 sum = vec3(0.0);
  uint found = 0u;
  for (uint s = 0u; s < sets; ++s) {
    if ((validMask & (1u << s)) == 0u) continue;
    ivec2 q = px;
    if ((sameCamera & (1u << s)) != 0u) {
      // Same camera, same pixel: an unchanged depth means the same surface point (no unprojection).
      uint i = s * layer + uint(px.y * size.x + px.x);
      if (setDepth[i] == depthNow) {
        sum += setIndirect[i].rgb;
        ++found;
        continue;
      }
    } else {
      vec4 clip = cameras[s].viewProj * vec4(p.xyz, 1.0);
      if (clip.w <= 0.0) continue;
      q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    }
    uint i = s * layer + uint(q.y * size.x + q.x);
    float d = setDepth[i];
    if (d < 0.0) continue;
    vec4 y = cameras[s].invViewProj * vec4((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0, d, 1.0);
    if (length(y.xyz / y.w - p.xyz) > tolerance) continue;
    sum += setIndirect[i].rgb;
    ++found;
  }
  imageStore(outAccumulated, px, vec4(found > 0u ? sum * float(sets) / float(found) : vec3(0.0), 1.0));
}
