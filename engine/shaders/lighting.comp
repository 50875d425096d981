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
layout(set = 0, binding = DYNGI_LIGHTING_BINDING_SPECULAR, rgba16f) uniform readonly image2D specular;
layout(push_constant) uniform Push { DYNGI_LIGHTING_PUSH };
// Where the indirect specular radiance comes from (SpecularSource): 0 none, 1 RenderTargets::specular,
// 2 the indirect diffuse light itself. A pipeline variant each.
layout(constant_id = 0) const uint kSpecular = 0u;

const float PI = 3.14159265358979;
#include "shared/shadows.glsl"

// The directional albedo of a GGX specular lobe, F0 * A + B, from Karis' analytic fit to the split-sum
// table ("Physically Based Shading on Mobile", 2014): what a prefiltered reflection is weighted by.
vec3 specularColour(vec3 f0, float roughness, float nDotV) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * nDotV)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  return f0 * ab.x + ab.y;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(frame.sizeAndCount.x) || px.y >= int(frame.sizeAndCount.y)) return;
  vec4 pos = imageLoad(gPosition, px);
  if (pos.w == 0.0) {
    imageStore(outHdr, px, vec4(frame.background.rgb, 1.0));
    return;
  }
  vec4 normalRough = imageLoad(gNormal, px);
  vec3 n = normalize(normalRough.xyz);
  vec4 albedoMetal = imageLoad(gAlbedo, px);
  vec3 diffuse = albedoMetal.rgb * (1.0 - albedoMetal.a) / PI;
  vec4 emissiveOcclusion = imageLoad(gEmissive, px);
  vec3 radiance = emissiveOcclusion.rgb;
  float occlusion = emissiveOcclusion.a;  // the material's occlusion texture: indirect light only
  // A do-while: lavapipe runs a for loop's body once more, masked, before it sees every lane has left,
  // which here would cost a whole light (shadow lookups included) per pixel.
  uint count = frame.sizeAndCount.z, i = 0u;
  do {
    if (i < count) radiance += diffuse * shadowedIrradiance(lights[i], pos.xyz, n);
  } while (++i < count);
  vec3 indirectLight = hasIndirect != 0u ? imageLoad(indirect, px).rgb : vec3(0.0);
  radiance += occlusion * albedoMetal.rgb * (1.0 - albedoMetal.a) * indirectLight;
  if (kSpecular != 0u) {
    // Dielectrics reflect 4 percent at normal incidence, metals their base colour.
    vec3 f0 = mix(vec3(0.04), albedoMetal.rgb, albedoMetal.a);
    float nDotV = clamp(dot(n, normalize(frame.cameraPos.xyz - pos.xyz)), 0.0, 1.0);
    vec3 specularLight = kSpecular == 2u ? indirectLight : imageLoad(specular, px).rgb;
    radiance += occlusion * specularColour(f0, normalRough.w, nDotV) * specularLight;
  }
  imageStore(outHdr, px, vec4(radiance, 1.0));
}
