#version 460
// The RSM's vertex stage for normal-textured meshes (GpuMesh::tangents at location 3).
#extension GL_GOOGLE_include_directive : require
#include "rsm_vertex.glsl"
layout(location = 3) in vec4 inTangent;
void main() { rsmVertex(inTangent); }
