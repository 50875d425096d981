// Temporal accumulation of one pixel, in two parts.
//
// Per pixel the running sum (rgb) is kept with the view depth it refers to and the number of sets in it
// (sums[].a, temporalSumTag). The gather, right after it computed the pixel's light for the set gathered this frame (so the
// light never goes through an image), stores it and calls temporalAccumulateIncremental: when the camera
// has not moved since the last frame and the pixel still shows the same surface (same depth), only set
// `set` changed and the sum is updated in O(1) (old value out, new value in). Every other pixel is queued
// for temporalAccumulateFull (temporal_reproject.comp): every set is reprojected into the current view
// and a stored sample counts when the surface it was gathered for lies within `cutoff` (relative to the
// view distance) of this pixel's surface. Sets that miss (disocclusion) are made up for by scaling the sum
// by T / count, so a pixel is never black while any set sees it. Depths are view depths (distance along
// the view axis): a set stored from the current camera is tested at the same pixel with one subtraction.
//
// Why two passes: lavapipe runs both sides of every branch for all lanes, so a reprojection loop in the
// gather costs every pixel even when none takes it; the queue makes the rare full path cost only the
// pixels that need it (all of them only when the camera moved).
//
// The per-pixel data lives in storage images at the pixel's own coordinates: lavapipe loads an image
// texel for 8 lanes at once where it reads a storage buffer lane by lane, and a reprojected pixel lands
// next to its neighbours' (after a camera move the reprojection ran 48 -> 28 ms at 512^2).
//
// Needs before inclusion: FrameUniforms `frame`, filter_input.glsl, AccumulatePush `acc`, the images
// setSamples (rg32ui 2D array, one layer per set: setSample()) and sums (rgba32f: rgb sum, a
// temporalSumTag), and with DYNGI_TEMPORAL_REPROJECT the uniform array cameras (TemporalSetCamera).

// A sum's tag: the view depth it refers to with the count of sets in it in the low 6 mantissa bits (T <=
// 32), so that the gather's O(1) update reads and writes one vec4 per pixel. Depths that differ only in
// those bits (7.6e-6 relative) count as the same surface, far inside the reprojection cut-off.
const uint kSumCountBits = 63u;
float temporalSumTag(float depth, uint count) { return uintBitsToFloat((floatBitsToUint(depth) & ~kSumCountBits) | count); }
bool temporalSumIsFor(vec4 s, float depth) { return (floatBitsToUint(s.a) & ~kSumCountBits) == (floatBitsToUint(depth) & ~kSumCountBits); }
uint temporalSumCount(vec4 s) { return floatBitsToUint(s.a) & kSumCountBits; }

// A set's sample, one rg32ui texel in layer k: x its light as RGB9E5 (shared exponent: 9 bits per
// channel, 0.2% of the largest), y the view depth it was gathered at (float bits; <= 0: no surface).
// Eight bytes a sample instead of a vec4's sixteen, read and written in one image access (two r32ui
// layers cost a second access: -1.3 ms a frame at 512^2).
// Powers of two are built from their exponent bits: lavapipe evaluates log2 and exp2 as polynomials,
// which made the packing a visible part of the gather (exact here, and cheaper).
float exp2i(int e) { return uintBitsToFloat(uint(e + 127) << 23); }  // 2^e, -126 <= e <= 127
uint packRgb9e5(vec3 c) {
  const float maxValue = 65408.0;  // (511 / 512) 2^16
  c = clamp(c, vec3(0.0), vec3(maxValue));
  float m = max(c.r, max(c.g, c.b));
  // floor(log2(m)) from the float's exponent (0 for zero and denormals, clamped to -16 like them).
  int e = max(-16, int(floatBitsToUint(m) >> 23) - 127) + 16;  // biased exponent before rounding
  float invScale = exp2i(15 + 9 - e);
  if (floor(m * invScale + 0.5) >= 512.0) {
    ++e;
    invScale *= 0.5;
  }
  uvec3 q = uvec3(min(floor(c * invScale + 0.5), vec3(511.0)));
  return q.r | (q.g << 9) | (q.b << 18) | (uint(e) << 27);
}
vec3 unpackRgb9e5(uint v) {
  return vec3(uvec3(v, v >> 9, v >> 18) & 511u) * exp2i(int(v >> 27) - 15 - 9);
}
vec4 setSample(ivec2 q, uint set) {
  uvec2 v = imageLoad(setSamples, ivec3(q, set)).xy;
  return vec4(unpackRgb9e5(v.x), uintBitsToFloat(v.y));
}

vec3 temporalAverage(vec3 sum, uint count) { return count > 0u ? sum * float(acc.setCount) / float(count) : vec3(0.0); }

// The gather's part for pixel px: stores newValue, this frame's light for set acc.currentSet at a surface of
// view depth `depth` (<= 0: none). Returns true with the filter input (filter_input.glsl) in `result`
// when the pixel is done (no surface, or the incremental update applied); false when it needs
// temporalAccumulateFull.
bool temporalAccumulateIncremental(ivec2 px, vec3 newValue, float depth, uvec2 packedNormal, out uvec4 result) {
  const uint set = acc.currentSet;
  // Store this frame's set (old value kept for the incremental update).
  vec4 oldValue = setSample(px, set);
  uint packedValue = packRgb9e5(newValue);
  imageStore(setSamples, ivec3(px, set), uvec4(packedValue, floatBitsToUint(depth > 0.0 ? depth : -1.0), 0u, 0u));
  newValue = unpackRgb9e5(packedValue);  // what is stored is what the sum holds: it comes out exactly
  const bool surface = depth > 0.0;
  vec4 s = imageLoad(sums, px);
  const bool incremental = surface && acc.incremental != 0u && temporalSumIsFor(s, depth);
  // Only set `set` changed: take its old sample out (if the full pass had counted it) and put the new one
  // in. The test is the full pass's test for a set stored from this camera.
  uint count = temporalSumCount(s);
  const bool replaces = acc.currentSetWasStored != 0u && oldValue.a > 0.0 && abs(oldValue.a - depth) <= acc.reprojectionCutoff * depth;
  s.rgb += newValue - (replaces ? oldValue.rgb : vec3(0.0));
  count += replaces ? 0u : 1u;
  // One store for both outcomes (lavapipe runs a store in a branch for every lane): the updated sum, or
  // for no surface a cleared one (a tag no surface's depth has). Queued pixels keep theirs: the full
  // reprojection rewrites it.
  if (incremental || !surface) imageStore(sums, px, surface ? vec4(s.rgb, temporalSumTag(depth, count)) : vec4(0.0));
  result = surface ? packFilterInput(depth, packedNormal, temporalAverage(s.rgb, count)) : uvec4(0u);
  return incremental || !surface;
}

#ifdef DYNGI_TEMPORAL_REPROJECT
// Set j's sample at this pixel, stored from the current camera: it counts when its depth is within the
// cut-off of this pixel's.
void addSameCameraSample(uint j, ivec2 px, float depth, float depthTolerance, inout vec3 sum, inout uint count) {
  vec4 stored = setSample(px, j);
  bool counts = stored.a > 0.0 && abs(stored.a - depth) <= depthTolerance;
  sum += counts ? stored.rgb : vec3(0.0);
  count += counts ? 1u : 0u;
}

// Set j's sample where world point p falls in its camera: it counts when the surface it was gathered
// for lies within `tolerance` of p. That point is y = camera + a ray(q) (a the stored view depth, ray(q)
// the unit-depth ray through the centre of the pixel q that p falls in), and p = camera + w ray(c) with
// c p's continuous pixel position and w its view depth, so
//   y - p = (a / w - 1) (p - camera) + a ((q + 0.5 - c).x rayStepX + (q + 0.5 - c).y rayStepY):
// exactly the old reconstruction, but it reads only the camera's position, its two pixel steps and
// three rows of its projection (clip z is never needed). On lavapipe each component of a set camera is a
// load per lane, and the struct copy had read all 32 (the reprojection after a camera move: 22.9 -> 21.7
// ms at 512^2).
void addReprojectedSample(uint j, vec3 p, float tolerance, ivec2 size, inout vec3 sum, inout uint count) {
  const vec4 p1 = vec4(p, 1.0);
  float cx = 0.0, cy = 0.0, cw = 0.0;  // clip x, y, w (column-major: viewProj[column][row])
  for (int c = 0; c < 4; ++c) {
    cx += cameras[j].viewProj[c][0] * p1[c];
    cy += cameras[j].viewProj[c][1] * p1[c];
    cw += cameras[j].viewProj[c][3] * p1[c];
  }
  vec2 continuous = (vec2(cx, cy) / cw * 0.5 + 0.5) * vec2(size);
  ivec2 q = ivec2(floor(continuous));
  bool inside = cw > 0.0 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
  vec4 stored = inside ? setSample(q, j) : vec4(0.0);
  vec2 offset = vec2(q) + 0.5 - continuous;
  vec3 d = (stored.a / cw - 1.0) * (p - cameras[j].position.xyz) +
           stored.a * (offset.x * cameras[j].pixelRayStepX.xyz + offset.y * cameras[j].pixelRayStepY.xyz);
  bool counts = stored.a > 0.0 && dot(d, d) <= tolerance * tolerance;
  sum += counts ? stored.rgb : vec3(0.0);
  count += counts ? 1u : 0u;
}

// The full reprojection for pixel px, whose light for this frame's set the gather stored; returns the
// filter input (filter_input.glsl).
uvec4 temporalAccumulateFull(ivec2 px, uvec2 packedNormal) {
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  const uint set = acc.currentSet, validMask = acc.storedSets, sameCamera = acc.setsFromThisCamera;
  vec4 own = setSample(px, set);
  float depth = own.a;
  float depthTolerance = acc.reprojectionCutoff * depth;
  vec3 sum = own.rgb;
  uint count = 1u;
  vec3 ray = pixelRay(px);
  vec3 p = frame.cameraPos.xyz + depth * ray;
  float tolerance = depthTolerance * length(ray);  // cutoff x distance to the camera
  uint others = validMask & ~(1u << set);
  // Two loops over uniform set masks, so a still camera (every set stored from it) never runs the
  // reprojection's arithmetic: lavapipe would run it for every set, masked, if both lived in one loop.
  // Do-whiles check at the end, which spares the masked extra pass lavapipe makes through a for loop.
  uint same = others & sameCamera;
  if (same != 0u) do {
    addSameCameraSample(uint(findLSB(same)), px, depth, depthTolerance, sum, count);
    same &= same - 1u;
  } while (same != 0u);
  uint moved = others & ~sameCamera;
  if (moved != 0u) do {
    uint j = uint(findLSB(moved));
    moved &= moved - 1u;
    addReprojectedSample(j, p, tolerance, size, sum, count);
  } while (moved != 0u);
  imageStore(sums, px, vec4(sum, temporalSumTag(depth, count)));
  return packFilterInput(depth, packedNormal, temporalAverage(sum, count));
}
#endif  // DYNGI_TEMPORAL_REPROJECT
