#version 460
// One shadow-map layer (shadow.frag writes the biased depth): the caster's instance to the light's view.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_SHADOW_BINDING_INSTANCES
#include "shared/draw_instances.glsl"
layout(push_constant) uniform Push { DYNGI_SHADOW_PUSH };
layout(location = 0) in vec3 inPosition;
void main() { gl_Position = lightViewProj * (drawModel(gl_InstanceIndex) * vec4(inPosition, 1.0)); }
