#version 460
// One shadow-map layer (shadow.frag writes the biased depth). The push constant is lightViewProj * model.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
layout(push_constant) uniform Push { DYNGI_SHADOW_PUSH };
layout(location = 0) in vec3 inPosition;
void main() { gl_Position = lightViewProjModel * vec4(inPosition, 1.0); }
