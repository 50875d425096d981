#version 460
// One shadow-map layer, an alpha-masked caster (glTF alphaMode MASK): cut where the base colour's alpha
// is under the material's threshold, then as shadow.frag.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shadow_depth.glsl"
layout(set = 0, binding = DYNGI_SHADOW_BINDING_BASE_COLOR_TEX) uniform sampler2D baseColorTex;
layout(location = 0) in vec2 inUv;
layout(location = 1) flat in float inThreshold;
void main() {
  if (texture(baseColorTex, inUv).a < inThreshold) discard;
  writeBiasedDepth();
}
