// The merge filter's input, one rgba32ui texel per pixel, so that each of the filter's K x K taps is a
// single fetch (three fetches per tap, position, normal and light, measured 2.5x slower on lavapipe):
//   x  view depth of the pixel's surface (float bits; 0: no surface),
//   y  its normal's x and y as half floats,
//   z  indirect light r and g as half floats (clamped to the half range),
//   w  low half: indirect light b; high half: the normal's z (half floats).
// Half floats decode in one instruction where the CPU has F16C (lavapipe); decoding an octahedral
// normal took half of the filter's time (3.5 of 7 ms at 512^2).
// The gather writes it (with the temporal technique: the accumulated light, temporal_accumulate.glsl).
// Needs FrameUniforms `frame` (shared/gpu_types.h) declared before inclusion.

float viewDepthOf(vec3 worldPos) { return dot(worldPos - frame.cameraPos.xyz, frame.viewForward.xyz); }

// Unit-view-depth ray through the centre of pixel px (see FrameUniforms).
vec3 pixelRay(ivec2 px) { return frame.pixelRay0.xyz + float(px.x) * frame.pixelRayStepX.xyz + float(px.y) * frame.pixelRayStepY.xyz; }

// A normal's part of the texel: (y, the high half of w).
uvec2 packFilterNormal(vec3 n) { return uvec2(packHalf2x16(n.xy), packHalf2x16(vec2(0.0, n.z))); }
uvec2 filterPackedNormal(uvec4 t) { return uvec2(t.y, t.w & 0xffff0000u); }

uvec4 packFilterInput(float viewDepth, uvec2 packedNormal, vec3 light) {
  light = clamp(light, vec3(0.0), vec3(65000.0));
  return uvec4(floatBitsToUint(viewDepth), packedNormal.x, packHalf2x16(light.rg), packHalf2x16(vec2(light.b, 0.0)) | packedNormal.y);
}

vec3 filterLight(uvec4 t) { return vec3(unpackHalf2x16(t.z), unpackHalf2x16(t.w).x); }
float filterViewDepth(uvec4 t) { return uintBitsToFloat(t.x); }
vec3 filterNormal(uvec4 t) { return vec3(unpackHalf2x16(t.y), unpackHalf2x16(t.w).y); }  // unit, to half precision
