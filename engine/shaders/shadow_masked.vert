#version 460
// One shadow-map layer, an alpha-masked caster: shadow.vert plus the texture coordinates the cut reads
// and its threshold.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/uv_transform.h"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_SHADOW_BINDING_INSTANCES
#include "shared/draw_instances.glsl"
layout(push_constant) uniform Push { DYNGI_SHADOW_PUSH };
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec2 outUv;
layout(location = 1) flat out float outThreshold;  // alphaMaskThreshold()
void main() {
  DrawInstance inst = drawInstance(gl_InstanceIndex);
  outUv = applyUvTransform(inst.uvLinear, inst.params.zw, inUv);
  outThreshold = inst.baseColor.a;
  gl_Position = lightViewProj * (inst.model * vec4(inPosition, 1.0));
}
