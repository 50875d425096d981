#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "shared/uv_transform.h"
layout(set = 0, binding = DYNGI_RSM_BINDING_LAYERS) readonly buffer Layers { RsmLayer layers[]; };
layout(push_constant) uniform Push { RsmPush pc; };
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
void main() {
  vec4 w = pc.model * vec4(inPosition, 1.0);
  outWorld = w.xyz;
  outNormal = transpose(inverse(mat3(pc.model))) * inNormal;
  outUv = applyUvTransform(pc.uvLinear, pc.uvOffset.xy, inUv);
  gl_Position = layers[pc.layer].viewProj * w;
}
