#version 460
// Reflective shadow map: per texel the surface the light sees first, its normal (facing the light) and
// the flux it reflects: rho * (the flux the light sends through this texel).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "many_lights_shared.h"
#include "shared/lighting.glsl"
#include "shared/normal_map.h"
layout(set = 0, binding = DYNGI_RSM_BINDING_LAYERS) readonly buffer Layers { RsmLayer layers[]; };
layout(set = 0, binding = DYNGI_RSM_BINDING_LIGHTS) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = DYNGI_RSM_BINDING_BASE_COLOR_TEX) uniform sampler2D baseColorTex;
layout(set = 0, binding = DYNGI_RSM_BINDING_METALLIC_ROUGHNESS_TEX) uniform sampler2D metallicRoughnessTex;
layout(set = 0, binding = DYNGI_RSM_BINDING_NORMAL_TEX) uniform sampler2D normalTex;
layout(push_constant) uniform Push { DYNGI_RSM_PUSH };
// Material variant (ManyLights::rsmPipelineFor): the lookup is compiled in only when a texture is bound.
layout(constant_id = 0) const bool kBaseColorTexture = true;
layout(constant_id = 1) const bool kMetallicRoughnessTexture = true;
layout(constant_id = 2) const bool kAlphaMask = false;  // alphaMode MASK: cut texels do not reflect (the light passes)
layout(constant_id = 3) const bool kNormalTexture = false;  // with rsm_tangent.vert
layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;
layout(location = 4) flat in vec4 inBaseColor;  // rsm_vertex.glsl
layout(location = 5) flat in vec2 inMaterial;
layout(location = 0) out vec4 outPosition;  // xyz world, w 1
layout(location = 1) out vec4 outNormal;    // xyz facing the light
layout(location = 2) out vec4 outFlux;      // rgb reflected flux (W), a luminance
void main() {
  RsmLayer drawn = layers[layer];
  GpuLight L = lights[drawn.lightIndex];
  vec3 albedo = inBaseColor.rgb;
  float alpha = 1.0;
  if (kBaseColorTexture) {
    vec4 texel = texture(baseColorTex, inUv);
    albedo *= texel.rgb;
    alpha = texel.a;
  }
  if (kAlphaMask && alpha < inBaseColor.a) discard;
  float metallic = inMaterial.x;
  if (kMetallicRoughnessTexture) metallic *= texture(metallicRoughnessTex, inUv).b;
  albedo *= 1.0 - metallic;  // the diffuse share
  vec3 n = normalize(inNormal);
  vec3 radiant = L.radiance.rgb * L.radiance.w;
  vec3 flux;
  // The VPL's normal faces the light: decided on the interpolated normal, applied to the normal
  // texture's too (as the G-buffer does for the camera and SceneSurfaces for a path).
  vec3 toSurface = drawn.orthographic == 1u ? L.directionRange.xyz : inWorld - L.positionType.xyz;
  float facing = dot(n, toSurface) > 0.0 ? -1.0 : 1.0;
  if (kNormalTexture) n = perturbNormal(n, inTangent, texture(normalTex, inUv).rgb, inMaterial.y);
  n *= facing;
  if (drawn.orthographic == 1u) {
    // Irradiance E on a plane facing the light times the texel's area across the beam.
    float texelSide = drawn.axis.w / float(drawn.resolution);
    flux = albedo * radiant * texelSide * texelSide;
  } else {
    vec3 d = inWorld - L.positionType.xyz;
    float dist = length(d);
    vec3 w = d / max(dist, 1e-6);
    float cosAxis = max(dot(w, drawn.axis.xyz), 1e-4);
    float texel = drawn.axis.w / float(drawn.resolution);
    float solidAngle = texel * texel * cosAxis * cosAxis * cosAxis;
    float atten = rangeWindow(dist, L.directionRange.w);
    if (int(L.positionType.w) == DYNGI_LIGHT_SPOT) atten *= spotFalloff(dot(w, L.directionRange.xyz), L.cone.x, L.cone.y);
    flux = albedo * radiant * solidAngle * atten;
  }
  outPosition = vec4(inWorld, 1.0);
  outNormal = vec4(n, 0.0);
  outFlux = vec4(flux, dot(flux, vec3(0.2126, 0.7152, 0.0722)));
}
