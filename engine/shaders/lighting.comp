#version 460
// Deferred lighting, the frame's radiance: emission + Lambert diffuse from every light, shadowed
// through the shadow-map array (PCF over a 3x3-texel tent), + albedo x the indirect light render
// features wrote (E_indirect / pi). Runs after the features: one pass instead of a direct pass and a
// composite pass (no direct image written and read back).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/lighting.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = DYNGI_LIGHTING_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_G_POSITION, rgba32f) uniform readonly image2D gPosition;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_G_NORMAL, rgba16f) uniform readonly image2D gNormal;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_G_ALBEDO, rgba8) uniform readonly image2D gAlbedo;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_G_EMISSIVE, rgba16f) uniform readonly image2D gEmissive;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_SHADOW_MATRICES) readonly buffer ShadowMatrices { mat4 shadowViewProj[]; };
// Per texel the nearest caster's biased depth (ShadowPass::shadowMap()).
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_SHADOW_MAPS, r32f) uniform readonly image2DArray shadowMaps;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_INDIRECT, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_OUT_HDR, rgba32f) uniform writeonly image2D outHdr;
layout(push_constant) uniform Push { DYNGI_LIGHTING_PUSH };

const float PI = 3.14159265358979;

// Point lights use six layers (+X,-X,+Y,-Y,+Z,-Z); pick the face the direction falls in.
uint cubeFace(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y > 0.0 ? 2u : 3u;
  return d.z > 0.0 ? 4u : 5u;
}

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

// Irradiance from light L at p (normal n), shadowed.
vec3 directLight(GpuLight L, vec3 p, vec3 n) {
  if (L.radiance.w == 0.0) return vec3(0.0);
  vec3 l;
  float dist;
  vec3 e = lightIrradiance(L, p, n, l, dist);
  if (max(e.r, max(e.g, e.b)) <= 0.0) return vec3(0.0);
  return e * shadowFactor(L, p, n, dist);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {
    imageStore(outHdr, px, vec4(frame.background.rgb, 1.0));
    return;
  }
  vec3 n = normalize(imageLoad(gNormal, px).xyz);
  vec4 albedoMetal = imageLoad(gAlbedo, px);
  vec3 diffuse = albedoMetal.rgb * (1.0 - albedoMetal.a) / PI;
  vec3 radiance = imageLoad(gEmissive, px).rgb;
  // A do-while: lavapipe runs a for loop's body once more, masked, before it sees every lane has left,
  // which here would cost a whole light (shadow lookups included) per pixel.
  uint count = frame.sizeAndCount.z, i = 0u;
  do {
    if (i < count) radiance += diffuse * directLight(lights[i], pos.xyz, n);
  } while (++i < count);
  if (hasIndirect != 0u) radiance += albedoMetal.rgb * (1.0 - albedoMetal.a) * imageLoad(indirect, px).rgb;
  imageStore(outHdr, px, vec4(radiance, 1.0));
}
