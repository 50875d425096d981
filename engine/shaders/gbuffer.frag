#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/normal_map.h"

layout(set = 0, binding = DYNGI_GBUFFER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_GBUFFER_BINDING_BASE_COLOR_TEX) uniform sampler2D baseColorTex;
layout(set = 0, binding = DYNGI_GBUFFER_BINDING_EMISSIVE_TEX) uniform sampler2D emissiveTex;
layout(set = 0, binding = DYNGI_GBUFFER_BINDING_METALLIC_ROUGHNESS_TEX) uniform sampler2D metallicRoughnessTex;
layout(set = 0, binding = DYNGI_GBUFFER_BINDING_OCCLUSION_TEX) uniform sampler2D occlusionTex;
layout(set = 0, binding = DYNGI_GBUFFER_BINDING_NORMAL_TEX) uniform sampler2D normalTex;
// Material variants (GBufferPass::pipelineFor): the texture lookups are compiled in only when used.
layout(constant_id = 0) const bool kBaseColorTexture = true;
layout(constant_id = 1) const bool kEmissiveTexture = true;
layout(constant_id = 2) const bool kMetallicRoughnessTexture = true;
layout(constant_id = 3) const bool kOcclusionTexture = true;
layout(constant_id = 4) const bool kAlphaMask = false;  // alphaMode MASK: inBaseColor.a is the texture-alpha threshold
layout(constant_id = 5) const bool kNormalTexture = false;  // with gbuffer_tangent.vert

layout(location = 0) in vec3 inWorldPos;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;
layout(location = 4) flat in vec4 inBaseColor;  // gbuffer_vertex.glsl
layout(location = 5) flat in vec3 inEmissive;
layout(location = 6) flat in vec4 inMaterial;   // metallic, roughness, occlusion strength, normal scale

layout(location = 0) out vec4 outPosition;  // xyz world, w 1 = geometry
layout(location = 1) out vec4 outNormal;    // xyz world normal facing the camera, w roughness
layout(location = 2) out vec4 outAlbedo;    // rgb linear base colour, a metallic
layout(location = 3) out vec4 outEmissive;  // rgb emitted radiance, a the share of indirect light that reaches it (occlusion texture)

void main() {
  vec4 base = vec4(inBaseColor.rgb, 1.0);
  if (kBaseColorTexture) base *= texture(baseColorTex, inUv);
  if (kAlphaMask && base.a < inBaseColor.a) discard;
  vec3 emissive = inEmissive;
  if (kEmissiveTexture) emissive *= texture(emissiveTex, inUv).rgb;
  float metallic = inMaterial.x, roughness = inMaterial.y;
  if (kMetallicRoughnessTexture) {
    vec4 mr = texture(metallicRoughnessTex, inUv);  // glTF: roughness in G, metallic in B
    roughness *= mr.g;
    metallic *= mr.b;
  }
  float occlusion = 1.0;
  if (kOcclusionTexture) occlusion = 1.0 + inMaterial.z * (texture(occlusionTex, inUv).r - 1.0);
  vec3 n = normalize(inNormal);
  // Surfaces are lit on the side the camera sees (glTF double-sided / thin walls): decided on the
  // interpolated normal, applied to the normal texture's too.
  bool back = dot(n, frame.cameraPos.xyz - inWorldPos) < 0.0;
  if (kNormalTexture) n = perturbNormal(n, inTangent, texture(normalTex, inUv).rgb, inMaterial.w);
  if (back) n = -n;
  outPosition = vec4(inWorldPos, 1.0);
  outNormal = vec4(n, roughness);
  outAlbedo = vec4(base.rgb, metallic);
  outEmissive = vec4(emissive, occlusion);
}
