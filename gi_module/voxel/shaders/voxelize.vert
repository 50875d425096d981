#version 460
#extension GL_GOOGLE_include_directive : require
#include "voxelize_vertex.glsl"
void main() { voxelizeVertex(vec3(0.0), vec4(0.0)); }
