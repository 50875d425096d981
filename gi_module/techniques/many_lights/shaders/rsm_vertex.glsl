// The RSM's vertex stage, shared by rsm.vert (meshes without a normal texture) and rsm_tangent.vert
// (normal-textured meshes, GpuMesh::tangents at location 3): world position, normal and tangent, the
// transformed texture coordinates.
#include "shared/gi_gpu_types.h"
#include "shared/uv_transform.h"
layout(set = 0, binding = DYNGI_RSM_BINDING_LAYERS) readonly buffer Layers { RsmLayer layers[]; };
layout(push_constant) uniform Push { RsmPush pc; };
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outTangent;  // xyz world, w the bitangent's sign; 0 without tangents
void rsmVertex(vec4 objectTangent) {
  vec4 w = pc.model * vec4(inPosition, 1.0);
  outWorld = w.xyz;
  outNormal = transpose(inverse(mat3(pc.model))) * inNormal;
  outTangent = vec4(mat3(pc.model) * objectTangent.xyz, objectTangent.w);
  outUv = applyUvTransform(pc.uvLinear, pc.uvOffset.xy, inUv);
  gl_Position = layers[pc.layer].viewProj * w;
}
