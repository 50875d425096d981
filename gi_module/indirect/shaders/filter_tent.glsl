// The geometry-aware merge filter, one axis of it (filter_rows.comp, then filter_columns.comp): a tent of
// width 2K - 1, weights K - |d|, over the neighbours on the pixel's surface (normals within ~25 degrees,
// positions close to its tangent plane).
//
// Why a tent: the taps of each residue mod K sum to K, so every sub-image of the K x K interleaving gets
// the same weight and the pattern cancels as with a K x K box; but a hot pixel of one sub-image (a VPL
// close to a surface) spreads as a smooth pyramid, where a box makes a K x K square with hard edges
// (tiles). Rows then columns: 2 (2K - 1) taps instead of (2K - 1)^2 (14 against 49 at K = 4), the
// surface test applied in each pass. The taps are branch-free (a SIMD device runs neighbouring pixels in
// lock step); each is one fetch of the packed input (filter_input.glsl).
// Needs `K` (specialization constant), FrameUniforms `frame`, `planeTolerance` and the readonly rgba32ui
// image `filterInput` declared before inclusion.
#include "filter_input.glsl"

// The filtered light at px along `axis` ((1, 0) or (0, 1)); false when px shows no surface.
bool tentFilter(ivec2 px, ivec2 axis, out uvec4 centre, out vec3 light) {
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  centre = imageLoad(filterInput, px);
  light = vec3(0.0);
  float t = filterViewDepth(centre);
  if (t <= 0.0) return false;
  vec3 n = normalize(filterNormal(centre));
  // Neighbour q's surface point is cameraPos + t_q ray(q), so its distance from this pixel's tangent
  // plane is t_q dot(ray(q), n) - t dot(ray(px), n), with dot(ray(q), n) affine in q.
  float rn0 = dot(frame.pixelRay0.xyz, n), rnx = dot(frame.pixelRayStepX.xyz, n), rny = dot(frame.pixelRayStepY.xyz, n);
  float planeOffset = t * dot(pixelRay(px), n);
  float scale = planeTolerance * t * length(pixelRay(px));  // the tolerance relative to the view distance
  // Centred on the pixel, shifted inward at the image's edges so that every tap exists (a clamped tap
  // would repeat the edge pixel's sub-image and leave another out: a pattern along the border).
  int k = int(K);
  ivec2 mid = px;
  int along = axis.x != 0 ? px.x : px.y, extent = axis.x != 0 ? size.x : size.y;
  along = clamp(along, k - 1, max(extent - k, k - 1));
  mid = axis.x != 0 ? ivec2(along, px.y) : ivec2(px.x, along);
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int d = 1 - k; d < k; ++d) {
    ivec2 q = clamp(mid + axis * d, ivec2(0), size - 1);
    uvec4 tap = imageLoad(filterInput, q);
    float tq = filterViewDepth(tap);
    vec3 nq = filterNormal(tap);
    // Same surface: foreground, normal within ~25 degrees (cos >= 0.9; nq is unit to half precision,
    // which moves the bound by ~0.03 degrees), close to the tangent plane.
    float plane = tq * (rn0 + float(q.x) * rnx + float(q.y) * rny) - planeOffset;
    bool same = tq > 0.0 && dot(n, nq) >= 0.9 && abs(plane) <= scale;
    float w = same ? float(k - abs(d)) : 0.0;
    sum += filterLight(tap) * w;
    wsum += w;
  }
  light = wsum > 0.0 ? sum / wsum : vec3(0.0);
  return true;
}
