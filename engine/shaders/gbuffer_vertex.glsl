// The G-buffer's vertex stage, shared by gbuffer.vert (meshes without tangents) and gbuffer_tangent.vert
// (normal-textured meshes): world position, normal and tangent, transformed texture coordinates.
#include "shared/gpu_types.h"
#include "shared/uv_transform.h"

layout(set = 0, binding = DYNGI_GBUFFER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { GBufferPush pc; };

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outTangent;  // xyz world, w the bitangent's sign; 0 without tangents

void gbufferVertex(vec4 objectTangent) {
  vec4 world = pc.model * vec4(inPosition, 1.0);
  outWorldPos = world.xyz;
  // Inverse-transpose keeps normals right under non-uniform scale; tangents lie in the surface and
  // move with it.
  outNormal = transpose(inverse(mat3(pc.model))) * inNormal;
  outTangent = vec4(mat3(pc.model) * objectTangent.xyz, objectTangent.w);
  outUv = applyUvTransform(pc.uvLinear, pc.params.zw, inUv);
  gl_Position = frame.viewProj * world;
}
