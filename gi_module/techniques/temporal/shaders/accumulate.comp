#version 460
// Temporal accumulation, one pass: store the set just gathered (`set`), then produce the sum over all
// sets for the current view.
//
// Per pixel the running sum (rgb) and the number of sets in it (a) are kept with the view depth they
// refer to. When the camera has not moved since the last frame and the pixel still shows the same
// surface (same depth), only set `set` changed: the sum is updated in O(1) (old value out, new value in).
// Otherwise every set is reprojected into the current view: a stored sample counts when the surface it
// was gathered for lies within `cutoff` (relative to the view distance) of this pixel's surface. Sets
// that miss (disocclusion) are made up for by scaling the sum by T / count, so a pixel is never black
// while any set sees it. Depths are view depths (distance along the view axis): a set stored from the
// current camera is tested at the same pixel with one subtraction, no matrix.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimage2D raw;  // this frame's gather (filter_input.glsl)
layout(set = 0, binding = 2) buffer SetIndirect { vec4 setIndirect[]; };  // rgb light, a view depth (<= 0: none)
layout(set = 0, binding = 3) readonly buffer Cameras { TemporalSetCamera cameras[]; };
layout(set = 0, binding = 4) buffer Sums { vec4 sums[]; };       // rgb sum, a sets counted
layout(set = 0, binding = 5) buffer SumDepths { float sumDepths[]; };
layout(set = 0, binding = 6, rgba32ui) uniform writeonly uimage2D outAccumulated;  // the filter's input
layout(push_constant) uniform Push { AccumulatePush pc; };
#include "filter_input.glsl"

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  uint pixel = uint(px.y * size.x + px.x);
  uint layer = uint(size.x * size.y);
  const uint sets = pc.sets.x, set = pc.sets.y, validMask = pc.sets.z, sameCamera = pc.sets.w;
  const float cutoff = pc.params.x;
  // The gather's texel carries this pixel's view depth and normal.
  uvec4 gathered = imageLoad(raw, px);
  float depth = filterViewDepth(gathered);
  // Store this frame's set (old value kept for the incremental update).
  uint ik = set * layer + pixel;
  vec4 oldValue = setIndirect[ik];
  vec3 newValue = filterLight(gathered);
  setIndirect[ik] = vec4(newValue, depth > 0.0 ? depth : -1.0);
  if (depth <= 0.0) {
    sums[pixel] = vec4(0.0);
    sumDepths[pixel] = -1.0;
    imageStore(outAccumulated, px, uvec4(0u));
    return;
  }
  // Same surface along this pixel's ray: view depths within cutoff x depth (the distance along the ray
  // scales both sides alike).
  float depthTolerance = cutoff * depth;
  vec4 s;
  if (pc.mode.x != 0u && sumDepths[pixel] == depth) {
    // Only set `set` changed: take its old sample out (if the full pass had counted it) and put the
    // new one in. The test is the full pass's test for a set stored from this camera.
    s = sums[pixel];
    if (pc.mode.y != 0u && oldValue.a > 0.0 && abs(oldValue.a - depth) <= depthTolerance) s.rgb -= oldValue.rgb;
    else s.a += 1.0;
    s.rgb += newValue;
  } else {
    s = vec4(newValue, 1.0);
    vec3 p = frame.cameraPos.xyz + depth * pixelRay(px);
    float tolerance = depthTolerance * length(pixelRay(px));  // cutoff x distance to the camera
    for (uint j = 0u; j < sets; ++j) {
      if (j == set || (validMask & (1u << j)) == 0u) continue;
      if ((sameCamera & (1u << j)) != 0u) {
        vec4 stored = setIndirect[j * layer + pixel];
        if (stored.a > 0.0 && abs(stored.a - depth) <= depthTolerance) s += vec4(stored.rgb, 1.0);
        continue;
      }
      TemporalSetCamera c = cameras[j];
      vec4 clip = c.viewProj * vec4(p, 1.0);
      if (clip.w <= 0.0) continue;
      ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 stored = setIndirect[j * layer + uint(q.y * size.x + q.x)];
      if (stored.a <= 0.0) continue;
      vec3 y = c.position.xyz + stored.a * (c.pixelRay0.xyz + float(q.x) * c.pixelRayStepX.xyz + float(q.y) * c.pixelRayStepY.xyz);
      if (length(y - p) > tolerance) continue;
      s += vec4(stored.rgb, 1.0);
    }
    sumDepths[pixel] = depth;
  }
  sums[pixel] = s;
  vec3 light = s.a > 0.0 ? s.rgb * float(sets) / s.a : vec3(0.0);
  imageStore(outAccumulated, px, uvec4(gathered.xy, packFilterLight(light)));
}
