#version 460
// The G-buffer's vertex stage for normal-textured meshes (GpuMesh::tangents at location 3).
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_vertex.glsl"
layout(location = 3) in vec4 inTangent;
void main() { gbufferVertex(inTangent); }
