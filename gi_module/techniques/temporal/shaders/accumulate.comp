#version 460
// Temporal accumulation, one pass: store the set just gathered (`set`), then produce the sum over all
// sets for the current view.
//
// Per pixel the running sum (rgb) and the number of sets in it (a) are kept with the depth they refer
// to. When the camera has not moved since the last frame and the pixel still shows the same surface
// (same depth), only set `set` changed: the sum is updated in O(1) (old value out, new value in).
// Otherwise every set is reprojected into the current view: a stored sample counts when the surface it
// was gathered for lies within `cutoff` (relative to the view distance) of this pixel's surface. Sets
// that miss (disocclusion) are made up for by scaling the sum by T / count, so a pixel is never black
// while any set sees it.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimage2D raw;  // this frame's gather (filter_input.glsl)
layout(set = 0, binding = 2) buffer SetIndirect { vec4 setIndirect[]; };  // rgb light, a NDC depth (< 0: none)
struct SetCamera { mat4 viewProj; mat4 invViewProj; };
layout(set = 0, binding = 3) readonly buffer Cameras { SetCamera cameras[]; };
layout(set = 0, binding = 4) buffer Sums { vec4 sums[]; };       // rgb sum, a sets counted
layout(set = 0, binding = 5) buffer SumDepths { float sumDepths[]; };
layout(set = 0, binding = 6, rgba32ui) uniform writeonly uimage2D outAccumulated;  // the filter's input
layout(push_constant) uniform Push {
  uint sets;
  uint set;         // the set gathered this frame
  uint validMask;   // sets stored at least once (including `set`)
  uint incremental; // 1: the camera is where it was last frame, set `set` was last stored from this
                    // camera too, and the running sums are current
  float cutoff;
  uint setWasStored; // 1: `set` held a sample before this frame (its old value is in the buffers)
};

#include "filter_input.glsl"

// Whether a sample stored from the current camera at this pixel with NDC depth d is of surface p.
bool sameSurface(vec2 pixelCentre, float d, vec3 p, float tolerance) {
  if (d < 0.0) return false;
  vec4 y = frame.invViewProj * vec4(pixelCentre / vec2(frame.sizeAndCount.xy) * 2.0 - 1.0, d, 1.0);
  return length(y.xyz / y.w - p) <= tolerance;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  uint pixel = uint(px.y * size.x + px.x);
  uint layer = uint(size.x * size.y);
  // The gather's texel carries this pixel's view depth and normal; the surface point follows from it.
  uvec4 gathered = imageLoad(raw, px);
  float viewDepth = filterViewDepth(gathered);
  vec3 p = frame.cameraPos.xyz + viewDepth * pixelRay(px);
  float depthNow = -1.0;
  if (viewDepth > 0.0) {
    vec4 clip = frame.viewProj * vec4(p, 1.0);
    depthNow = clip.z / clip.w;
  }
  // Store this frame's set (old value kept for the incremental update).
  uint ik = set * layer + pixel;
  vec4 oldValue = setIndirect[ik];
  vec3 newValue = filterLight(gathered);
  setIndirect[ik] = vec4(newValue, depthNow);
  if (depthNow < 0.0) {
    sums[pixel] = vec4(0.0);
    sumDepths[pixel] = -1.0;
    imageStore(outAccumulated, px, uvec4(0u));
    return;
  }
  float tolerance = cutoff * max(length(p - frame.cameraPos.xyz), 1e-3);
  vec4 s;
  if (incremental != 0u && sumDepths[pixel] == depthNow) {
    // Only set `set` changed: take its old sample out (if the full pass had counted it) and put the
    // new one in. The test is the full pass's test for a set stored from this camera.
    s = sums[pixel];
    if (setWasStored != 0u && sameSurface(vec2(px) + 0.5, oldValue.a, p, tolerance)) s.rgb -= oldValue.rgb;
    else s.a += 1.0;
    s.rgb += newValue;
  } else {
    s = vec4(newValue, 1.0);
    for (uint j = 0u; j < sets; ++j) {
      if (j == set || (validMask & (1u << j)) == 0u) continue;
      vec4 clip = cameras[j].viewProj * vec4(p, 1.0);
      if (clip.w <= 0.0) continue;
      ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 stored = setIndirect[j * layer + uint(q.y * size.x + q.x)];
      if (stored.a < 0.0) continue;
      vec4 y = cameras[j].invViewProj * vec4((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0, stored.a, 1.0);
      if (length(y.xyz / y.w - p) > tolerance) continue;
      s += vec4(stored.rgb, 1.0);
    }
    sumDepths[pixel] = depthNow;
  }
  sums[pixel] = s;
  vec3 light = s.a > 0.0 ? s.rgb * float(sets) / s.a : vec3(0.0);
  imageStore(outAccumulated, px, uvec4(gathered.xy, packFilterLight(light)));
}
