#version 460
// One shadow-map layer, an alpha-masked caster: shadow.vert plus the texture coordinates the cut reads.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/uv_transform.h"
layout(push_constant) uniform Push { DYNGI_SHADOW_PUSH };
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec2 outUv;
void main() {
  outUv = applyUvTransform(uvLinear, uvOffsetThreshold.xy, inUv);
  gl_Position = lightViewProjModel * vec4(inPosition, 1.0);
}
