#version 460
// One shadow-map layer (shadow.frag writes the biased depth). The push constant is lightViewProj * model.
layout(push_constant) uniform Push { mat4 lightViewProjModel; };
layout(location = 0) in vec3 inPosition;
void main() { gl_Position = lightViewProjModel * vec4(inPosition, 1.0); }
