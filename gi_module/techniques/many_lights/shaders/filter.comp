#version 460
// Geometry-aware merge filter: each pixel averages the K x K neighbourhood (one pixel of every
// sub-image) over neighbours on the same surface: normals within ~25 degrees and positions close to
// the pixel's tangent plane. Removes the interleaving pattern without blurring across edges.
// K is a specialization constant so the tap loops unroll; the taps are branch-free (lavapipe runs
// 8 pixels in lock step, and a G-buffer fetch in shared memory measured slower than the fetch itself).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint K = 4u;
layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gPosition;
layout(set = 0, binding = 2) uniform sampler2D gNormal;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D raw;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D outIndirect;
layout(push_constant) uniform Push { float planeTolerance; };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  if (px.x >= size.x || px.y >= size.y) return;
  vec4 p = texelFetch(gPosition, px, 0);
  if (p.w == 0.0) { imageStore(outIndirect, px, vec4(0.0)); return; }
  vec3 n = normalize(texelFetch(gNormal, px, 0).xyz);
  float scale = planeTolerance * max(length(p.xyz - frame.cameraPos.xyz), 1e-3);
  const int lo = -int(K) / 2;
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int dy = lo; dy < lo + int(K); ++dy)
    for (int dx = lo; dx < lo + int(K); ++dx) {
      ivec2 q = clamp(px + ivec2(dx, dy), ivec2(0), size - 1);
      vec4 pq = texelFetch(gPosition, q, 0);
      vec3 nq = texelFetch(gNormal, q, 0).xyz;
      // Same surface: foreground, normal within ~25 degrees (cos >= 0.9, nq unnormalised: squared
      // form), close to the tangent plane.
      float dn = dot(n, nq);
      bool same = pq.w != 0.0 && dn > 0.0 && dn * dn >= 0.81 * dot(nq, nq) && abs(dot(pq.xyz - p.xyz, n)) <= scale;
      float w = same ? 1.0 : 0.0;
      sum += imageLoad(raw, q).rgb * w;
      wsum += w;
    }
  imageStore(outIndirect, px, vec4(wsum > 0.0 ? sum / wsum : vec3(0.0), 1.0));
}
