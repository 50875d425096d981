// The merge filter's input, one rgba32ui texel per pixel, so that each of the filter's K x K taps is a
// single fetch (three fetches per tap, position, normal and light, measured 2.5x slower on lavapipe):
//   x  view depth of the pixel's surface (float bits; 0: no surface),
//   y  its normal, octahedral, snorm 2 x 16 bits (~0.003 rad),
//   zw indirect light rgb as half floats (clamped to the half range).
// The gather writes it (with the temporal technique: the accumulated light, temporal_accumulate.glsl).
// Needs FrameUniforms `frame` (shared/gpu_types.h) declared before inclusion.

vec2 octEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.xy;
  if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return e;
}

// Not normalized (length 1/sqrt(3)..1): callers that only compare angles skip the normalize.
vec3 octDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0);
  n.xy -= vec2(n.x >= 0.0 ? t : -t, n.y >= 0.0 ? t : -t);
  return n;
}

float viewDepthOf(vec3 worldPos) { return dot(worldPos - frame.cameraPos.xyz, frame.viewForward.xyz); }

// Unit-view-depth ray through the centre of pixel px (see FrameUniforms).
vec3 pixelRay(ivec2 px) { return frame.pixelRay0.xyz + float(px.x) * frame.pixelRayStepX.xyz + float(px.y) * frame.pixelRayStepY.xyz; }

uvec2 packFilterLight(vec3 light) {
  light = clamp(light, vec3(0.0), vec3(65000.0));
  return uvec2(packHalf2x16(light.rg), packHalf2x16(vec2(light.b, 0.0)));
}

uvec4 packFilterInput(float viewDepth, uint packedNormal, vec3 light) {
  return uvec4(floatBitsToUint(viewDepth), packedNormal, packFilterLight(light));
}
uint packFilterNormal(vec3 n) { return packSnorm2x16(octEncode(n)); }

vec3 filterLight(uvec4 t) { return vec3(unpackHalf2x16(t.z), unpackHalf2x16(t.w).x); }
float filterViewDepth(uvec4 t) { return uintBitsToFloat(t.x); }
vec3 filterNormal(uvec4 t) { return octDecode(unpackSnorm2x16(t.y)); }  // not normalized
