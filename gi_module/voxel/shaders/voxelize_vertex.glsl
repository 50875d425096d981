// The voxelization's vertex stage, shared by voxelize.vert and voxelize_tangent.vert (normal-textured
// meshes: their normals and GpuMesh::tangents at locations 1 and 3): positions in voxel units, the
// transformed texture coordinates, and for a normal texture the frame it turns, in voxel space.
#include "voxel_shared.h"
#include "shared/uv_transform.h"
layout(push_constant) uniform Push { VoxelizePush pc; };
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec3 outVoxelPos;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outNormal;   // 0 without a normal texture
layout(location = 3) out vec4 outTangent;  // xyz, w the bitangent's sign; 0 without a normal texture
void voxelizeVertex(vec3 objectNormal, vec4 objectTangent) {
  outVoxelPos = vec4(inPosition, 1.0) * pc.modelToVoxelRows;
  outUv = applyUvTransform(pc.uvLinear, pc.uvOffset.xy, inUv);
  // modelToVoxelRows holds the linear map's rows, so mat3(those rows) is its transpose: directions go
  // through the map as v * A, normals through the inverse transpose as inverse(A) * n.
  mat3 a = mat3(pc.modelToVoxelRows[0].xyz, pc.modelToVoxelRows[1].xyz, pc.modelToVoxelRows[2].xyz);
  outNormal = inverse(a) * objectNormal;
  outTangent = vec4(objectTangent.xyz * a, objectTangent.w);
  gl_Position = vec4(0.0);
}
