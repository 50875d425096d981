#version 460
// Geometry-aware merge filter: each pixel averages the K x K neighbourhood (one pixel of every
// sub-image) over neighbours on the same surface: normals within ~25 degrees and positions close to
// the pixel's tangent plane. Removes the interleaving pattern without blurring across edges.
// K is a specialization constant so the tap loops unroll; the taps are branch-free (lavapipe runs
// 8 pixels in lock step, and a fetch from shared memory measured slower than the fetch itself). Each
// tap is one fetch of the packed input (filter_input.glsl): depth, normal and light together.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint K = 4u;
layout(set = 0, binding = DYNGI_FILTER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_FILTER_BINDING_FILTER_INPUT, rgba32ui) uniform readonly uimage2D filterInput;
layout(set = 0, binding = DYNGI_FILTER_BINDING_OUT_INDIRECT, rgba32f) uniform writeonly image2D outIndirect;
layout(push_constant) uniform Push { DYNGI_INDIRECT_FILTER_PUSH };
#include "filter_input.glsl"
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  uvec4 centre = imageLoad(filterInput, px);
  float t = filterViewDepth(centre);
  if (t <= 0.0) { imageStore(outIndirect, px, vec4(0.0)); return; }
  vec3 n = normalize(filterNormal(centre));
  // Neighbour q's surface point is cameraPos + t_q ray(q), so its distance from this pixel's tangent
  // plane is t_q dot(ray(q), n) - t dot(ray(px), n), with dot(ray(q), n) affine in q.
  float rn0 = dot(frame.pixelRay0.xyz, n), rnx = dot(frame.pixelRayStepX.xyz, n), rny = dot(frame.pixelRayStepY.xyz, n);
  vec3 ray = pixelRay(px);
  float planeOffset = t * dot(ray, n);
  float scale = planeTolerance * t * length(ray);  // the tolerance relative to the view distance
  // The K x K window, shifted inward at the image's edges so that it always holds K distinct columns
  // and rows, one pixel of every sub-image (a clamped window would repeat the edge pixel's sub-image
  // and leave another out: a visible interleaving pattern along the border).
  ivec2 first = clamp(px - int(K) / 2, ivec2(0), max(size - int(K), ivec2(0)));
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int dy = 0; dy < int(K); ++dy)
    for (int dx = 0; dx < int(K); ++dx) {
      ivec2 q = min(first + ivec2(dx, dy), size - 1);
      uvec4 tap = imageLoad(filterInput, q);
      float tq = filterViewDepth(tap);
      vec3 nq = filterNormal(tap);
      // Same surface: foreground, normal within ~25 degrees (cos >= 0.9; nq is unit to half precision,
      // which moves the bound by ~0.03 degrees), close to the tangent plane.
      float plane = tq * (rn0 + float(q.x) * rnx + float(q.y) * rny) - planeOffset;
      bool same = tq > 0.0 && dot(n, nq) >= 0.9 && abs(plane) <= scale;
      float w = same ? 1.0 : 0.0;
      sum += filterLight(tap) * w;
      wsum += w;
    }
  imageStore(outIndirect, px, vec4(wsum > 0.0 ? sum / wsum : vec3(0.0), 1.0));
}
