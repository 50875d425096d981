#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/uv_transform.h"

layout(set = 0, binding = DYNGI_GBUFFER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { GBufferPush pc; };

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;

void main() {
  vec4 world = pc.model * vec4(inPosition, 1.0);
  outWorldPos = world.xyz;
  // Inverse-transpose keeps normals right under non-uniform scale.
  outNormal = transpose(inverse(mat3(pc.model))) * inNormal;
  outUv = applyUvTransform(pc.uvLinear, pc.params.zw, inUv);
  gl_Position = frame.viewProj * world;
}
