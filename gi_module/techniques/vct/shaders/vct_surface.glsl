// The surface a traced pixel saw, as vct_reproject.comp records it for every traced pixel each frame
// (rgba32ui, one texel a traced pixel): the point's float bits, and the normal in signed bytes with 127
// in the fourth (0 there: background). The filter and the upsample read their traced neighbours'
// surfaces from this small image instead of two full-resolution G-buffer images at scattered pixels;
// next frame's reprojection reads it as last frame's.
#ifndef DYNGI_VCT_SURFACE_GLSL
#define DYNGI_VCT_SURFACE_GLSL

uvec4 vctPackSurface(vec3 p, vec3 n) { return uvec4(floatBitsToUint(p), packSnorm4x8(vec4(n, 1.0))); }

// False for background (nothing seen there).
bool vctUnpackSurface(uvec4 s, out vec3 p, out vec3 n) {
  p = uintBitsToFloat(s.xyz);
  n = unpackSnorm4x8(s.w).xyz;
  return s.w != 0u;
}

#endif
