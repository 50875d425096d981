// Temporal accumulation of one pixel, run by the gather right after it computed the pixel's light for
// the set gathered this frame (so the light never goes through an image).
//
// Per pixel the running sum (rgb) and the number of sets in it (a) are kept with the view depth they
// refer to. When the camera has not moved since the last frame and the pixel still shows the same
// surface (same depth), only set `set` changed: the sum is updated in O(1) (old value out, new value in).
// Otherwise every set is reprojected into the current view: a stored sample counts when the surface it
// was gathered for lies within `cutoff` (relative to the view distance) of this pixel's surface. Sets
// that miss (disocclusion) are made up for by scaling the sum by T / count, so a pixel is never black
// while any set sees it. Depths are view depths (distance along the view axis): a set stored from the
// current camera is tested at the same pixel with one subtraction, no matrix.
//
// The per-pixel buffers are stored sub-image major (temporalIndex), the order the gather's workgroups
// walk, so a workgroup reads and writes contiguous memory.
//
// Needs before inclusion: FrameUniforms `frame`, filter_input.glsl, AccumulatePush `acc`, and the
// buffers setIndirect (vec4 per set and pixel: rgb light, a view depth, <= 0 none), cameras
// (TemporalSetCamera per set), sums (vec4 per pixel: rgb sum, a sets counted), sumDepths (float).

uint temporalIndex(ivec2 q, uint K) {
  uvec2 sub = uvec2(q) / K, subSize = acc.mode.zw;
  uint s = uint(q.x) % K + K * (uint(q.y) % K);
  return (s * subSize.y + sub.y) * subSize.x + sub.x;
}

// Returns the filter's input for pixel px (filter_input.glsl), newValue being this frame's light for
// set acc.sets.y at a surface of view depth `depth` (<= 0: none) with packed normal `packedNormal`.
uvec4 temporalAccumulate(ivec2 px, uint K, vec3 newValue, float depth, uint packedNormal) {
  ivec2 size = ivec2(frame.sizeAndCount.xy);
  const uint layer = acc.mode.z * acc.mode.w * K * K;
  const uint sets = acc.sets.x, set = acc.sets.y, validMask = acc.sets.z, sameCamera = acc.sets.w;
  const float cutoff = acc.params.x;
  uint pixel = temporalIndex(px, K);
  // Store this frame's set (old value kept for the incremental update).
  uint ik = set * layer + pixel;
  vec4 oldValue = setIndirect[ik];
  setIndirect[ik] = vec4(newValue, depth > 0.0 ? depth : -1.0);
  if (depth <= 0.0) {
    sums[pixel] = vec4(0.0);
    sumDepths[pixel] = -1.0;
    return uvec4(0u);
  }
  // Same surface along this pixel's ray: view depths within cutoff x depth.
  float depthTolerance = cutoff * depth;
  vec4 s;
  if (acc.mode.x != 0u && sumDepths[pixel] == depth) {
    // Only set `set` changed: take its old sample out (if the full pass had counted it) and put the
    // new one in. The test is the full pass's test for a set stored from this camera.
    s = sums[pixel];
    if (acc.mode.y != 0u && oldValue.a > 0.0 && abs(oldValue.a - depth) <= depthTolerance) s.rgb -= oldValue.rgb;
    else s.a += 1.0;
    s.rgb += newValue;
  } else {
    s = vec4(newValue, 1.0);
    vec3 ray = pixelRay(px);
    vec3 p = frame.cameraPos.xyz + depth * ray;
    float tolerance = depthTolerance * length(ray);  // cutoff x distance to the camera
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
      vec4 stored = setIndirect[j * layer + temporalIndex(q, K)];
      if (stored.a <= 0.0) continue;
      vec3 y = c.position.xyz + stored.a * (c.pixelRay0.xyz + float(q.x) * c.pixelRayStepX.xyz + float(q.y) * c.pixelRayStepY.xyz);
      if (length(y - p) > tolerance) continue;
      s += vec4(stored.rgb, 1.0);
    }
    sumDepths[pixel] = depth;
  }
  sums[pixel] = s;
  vec3 light = s.a > 0.0 ? s.rgb * float(sets) / s.a : vec3(0.0);
  return packFilterInput(depth, packedNormal, light);
}
