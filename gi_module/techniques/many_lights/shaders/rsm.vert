#version 460
#extension GL_GOOGLE_include_directive : require
#include "rsm_vertex.glsl"
void main() { rsmVertex(vec4(0.0)); }
