#version 460
// A host's G-buffer (gi::GiContext) into the GI's targets, pixel for pixel: world position from the
// depth (reversed or not) through the GI's camera, the normal decoded (world or view space, xyz or
// octahedral, with its scale and bias) and turned to face the camera as dyngi's G-buffer does,
// roughness and metallic from their channels, base colour, emission. Where the depth is the far plane
// nothing was hit: position and normal 0, as dyngi's G-buffer leaves its background.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/gi_gpu_types.h"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_DEPTH) uniform sampler2D hostDepth;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_NORMAL) uniform sampler2D hostNormal;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_BASE_COLOR) uniform sampler2D hostBaseColor;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_ROUGHNESS) uniform sampler2D hostRoughness;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_METALLIC) uniform sampler2D hostMetallic;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_EMISSIVE) uniform sampler2D hostEmissive;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_OUT_POSITION, rgba32f) uniform writeonly image2D outPosition;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_OUT_NORMAL, rgba16f) uniform writeonly image2D outNormal;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_OUT_ALBEDO, rgba8) uniform writeonly image2D outAlbedo;
layout(set = 0, binding = DYNGI_GBUFFER_IMPORT_BINDING_OUT_EMISSIVE, rgba16f) uniform writeonly image2D outEmissive;
layout(push_constant) uniform Push { DYNGI_GBUFFER_IMPORT_PUSH };

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n;
}

float channel(vec4 v, uint c) { return c == 0u ? v.r : c == 1u ? v.g : c == 2u ? v.b : c == 3u ? v.a : 0.0; }

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(width) || px.y >= int(height)) return;
  float depth = texelFetch(hostDepth, px, 0).r;
  float standardDepth = reversedZ == 1u ? 1.0 - depth : depth;  // the GI's projection is the host's, made standard
  vec4 base = texelFetch(hostBaseColor, px, 0);
  float roughness = channel(texelFetch(hostRoughness, px, 0), roughnessChannel);
  if (squaredRoughness == 1u) roughness = sqrt(max(roughness, 0.0));
  float metallic = channel(texelFetch(hostMetallic, px, 0), metallicChannel);
  imageStore(outAlbedo, px, vec4(base.rgb, metallic));
  imageStore(outEmissive, px, vec4(texelFetch(hostEmissive, px, 0).rgb, 0.0));
  if (standardDepth >= 1.0) {  // the far plane: nothing hit
    imageStore(outPosition, px, vec4(0.0));
    imageStore(outNormal, px, vec4(0.0, 0.0, 0.0, roughness));
    return;
  }
  vec2 ndc = (vec2(px) + 0.5) / vec2(width, height) * 2.0 - 1.0;
  vec4 p = frame.invViewProj * vec4(ndc, standardDepth, 1.0);
  vec3 position = p.xyz / p.w;
  vec4 stored = texelFetch(hostNormal, px, 0);
  vec3 n;
  if (normalEncoding == DYNGI_NORMAL_WORLD_OCTAHEDRAL || normalEncoding == DYNGI_NORMAL_VIEW_OCTAHEDRAL)
    n = octahedralDecode(stored.xy * normalScale + normalBias);
  else
    n = stored.xyz * normalScale + normalBias;
  if (normalEncoding == DYNGI_NORMAL_VIEW_XYZ || normalEncoding == DYNGI_NORMAL_VIEW_OCTAHEDRAL)
    n = transpose(mat3(frame.view)) * n;  // the view's rotation undone
  n = normalize(n);
  if (dot(n, frame.cameraPos.xyz - position) < 0.0) n = -n;  // facing the camera, as dyngi's G-buffer
  imageStore(outPosition, px, vec4(position, 1.0));
  imageStore(outNormal, px, vec4(n, roughness));
}
