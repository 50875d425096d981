// The voxelization's vertex stage, shared by voxelize.vert and voxelize_tangent.vert (normal-textured
// meshes: their normals and GpuMesh::tangents at locations 1 and 3): positions in voxel units, the
// transformed texture coordinates, for a normal texture the frame it turns, in voxel space, and the
// instance's material and fragment range for the later stages.
#include "shared/gpu_types.h"
#include "voxel_shared.h"
#include "shared/uv_transform.h"
#define DYNGI_DRAW_INSTANCES_BINDING DYNGI_VOXELIZE_BINDING_INSTANCES
#include "shared/draw_instances.glsl"
layout(set = 0, binding = DYNGI_VOXELIZE_BINDING_RANGES) readonly buffer Ranges { VoxelizeRange ranges[]; };
layout(push_constant) uniform Push { VoxelizePush pc; };
layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec3 outVoxelPos;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outNormal;   // 0 without a normal texture
layout(location = 3) out vec4 outTangent;  // xyz, w the bitangent's sign; 0 without a normal texture
layout(location = 4) flat out vec4 outAlbedo;     // rgb base colour factor, a metallic factor
layout(location = 5) flat out vec4 outEmission;   // rgb emitted radiance, a the alpha mask's threshold
layout(location = 6) flat out uvec4 outRange;     // VoxelizeRange: first slot, capacity, counter; w the normal scale's bits
void voxelizeVertex(vec3 objectNormal, vec4 objectTangent) {
  DrawInstance inst = drawInstance(gl_InstanceIndex);
  mat4 modelToVoxel = pc.worldToVoxel * inst.model;
  outVoxelPos = (modelToVoxel * vec4(inPosition, 1.0)).xyz;
  outUv = applyUvTransform(inst.uvLinear, inst.params.zw, inUv);
  // Directions go through the linear map A, normals through its inverse transpose.
  mat3 a = mat3(modelToVoxel);
  outNormal = transpose(inverse(a)) * objectNormal;
  outTangent = vec4(a * objectTangent.xyz, objectTangent.w);
  VoxelizeRange r = ranges[gl_InstanceIndex];
  outAlbedo = vec4(inst.baseColor.rgb, inst.params.x);
  outEmission = vec4(inst.emissive.rgb, inst.baseColor.a);
  outRange = uvec4(r.firstSlot, r.capacity, r.counterIndex, floatBitsToUint(unpackHalf2x16(floatBitsToUint(inst.emissive.w)).y));
  gl_Position = vec4(0.0);
}
