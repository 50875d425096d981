#version 460
// The voxelization's vertex stage for normal-textured meshes.
#extension GL_GOOGLE_include_directive : require
#include "voxelize_vertex.glsl"
layout(location = 1) in vec3 inNormal;
layout(location = 3) in vec4 inTangent;
void main() { voxelizeVertex(inNormal, inTangent); }
