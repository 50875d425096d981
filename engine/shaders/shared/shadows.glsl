// Shadow-map lookups: the lighting pass's, shared with features that light something themselves (radiance
// injection into a voxel volume). The includer declares, before including:
//   readonly buffer ... { mat4 shadowViewProj[]; };        one view-projection per shadow layer
//   layout(r32f) uniform readonly image2DArray shadowMaps;  the lookup layers (ShadowPass::shadowMap())
#ifndef DYNGI_SHADOWS_GLSL
#define DYNGI_SHADOWS_GLSL

// Point lights use six layers (+X,-X,+Y,-Y,+Z,-Z); pick the face the direction falls in.
uint cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y > 0.0 ? 2u : 3u;
  return d.z > 0.0 ? 4u : 5u;
}

// Fraction of light L reaching p (normal n, at `dist` from the light), 3x3-texel tent PCF.
float shadowFactor(GpuLight L, vec3 p, vec3 n, float dist) {
  if (L.cone.z < 0.0) return 1.0;
  uint layer = uint(L.cone.z);
  int type = int(L.positionType.w);
  // Normal offset grows with the texel footprint (distance for perspective maps).
  float offset = L.cone.w * (type == DYNGI_LIGHT_DIRECTIONAL ? 1.0 : dist);
  vec3 ps = p + n * offset;
  if (type == DYNGI_LIGHT_POINT) layer += cubeFace(ps - L.positionType.xyz);
  vec4 clip = shadowViewProj[layer] * vec4(ps, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  // The 3x3-texel tent of four bilinear comparisons half a texel off the position, from the nine texels
  // themselves: with the position t in texels (texel i spans [i, i + 1)), the taps cover texels
  // floor(t) - 1 .. floor(t) + 1 with weights (1 - f) / 2, 1 / 2, f / 2 per axis, f = fract(t).
  // Nine storage-image loads cost lavapipe less than four filtered comparison samples.
  ivec2 size = imageSize(shadowMaps).xy;
  vec2 t = uv * vec2(size);
  ivec2 first = ivec2(floor(t)) - 1;
  vec2 f = fract(t);
  vec3 wx = vec3(1.0 - f.x, 1.0, f.x) * 0.5, wy = vec3(1.0 - f.y, 1.0, f.y) * 0.5;
  float sum = 0.0;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      ivec2 q = clamp(first + ivec2(x, y), ivec2(0), size - 1);
      sum += ndc.z <= imageLoad(shadowMaps, ivec3(q, int(layer))).r ? wx[x] * wy[y] : 0.0;
    }
  return sum;
}

// Irradiance from light L at p (normal n), shadowed: what the lighting pass multiplies by albedo / pi.
// Needs shared/lighting.glsl included before.
vec3 shadowedIrradiance(GpuLight L, vec3 p, vec3 n) {
  if (L.radiance.w == 0.0) return vec3(0.0);
  vec3 l;
  float dist;
  vec3 e = lightIrradiance(L, p, n, l, dist);
  if (max(e.r, max(e.g, e.b)) <= 0.0) return vec3(0.0);
  return e * shadowFactor(L, p, n, dist);
}

#endif
