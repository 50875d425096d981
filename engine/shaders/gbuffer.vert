#version 460
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_vertex.glsl"
void main() { gbufferVertex(vec4(0.0)); }
