#version 460
#extension GL_GOOGLE_include_directive : require
#include "shared/gi_gpu_types.h"
#include "shared/uv_transform.h"
layout(push_constant) uniform Push { VoxelizePush pc; };
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec3 outVoxelPos;
layout(location = 1) out vec2 outUv;
void main() {
  outVoxelPos = vec4(inPosition, 1.0) * pc.modelToVoxelRows;
  outUv = applyUvTransform(pc.uvLinear, pc.uvOffset.xy, inUv);
  gl_Position = vec4(0.0);
}
