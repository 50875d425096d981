// The raster passes' vertex stage (the G-buffer's, the RSMs'): a mesh vertex to world space, with the
// interface their fragment stages read. Normals go through the inverse transpose (right under
// non-uniform scale); tangents lie in the surface and move with it; texture coordinates go through
// KHR_texture_transform (uv_transform.h). The tangent variants declare location 3's input themselves.
#include "shared/uv_transform.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outWorldPos;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outTangent;  // xyz world, w the bitangent's sign; 0 without tangents

// Writes the outputs; returns the world position.
vec4 meshVertex(mat4 model, vec4 uvLinear, vec2 uvOffset, vec4 objectTangent) {
  vec4 world = model * vec4(inPosition, 1.0);
  outWorldPos = world.xyz;
  outNormal = transpose(inverse(mat3(model))) * inNormal;
  outTangent = vec4(mat3(model) * objectTangent.xyz, objectTangent.w);
  outUv = applyUvTransform(uvLinear, uvOffset, inUv);
  return world;
}
