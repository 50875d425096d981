#version 460
// The host's G-buffer: world position to clip space (reversed-Z projection), world normal out.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
struct Draw {
  mat4 model;
  vec4 baseColor;          // rgb base colour, a metallic
  vec4 emissiveRoughness;  // rgb emitted radiance, a roughness
};
layout(set = 0, binding = 0) readonly buffer Draws { Draw draws[]; };
layout(push_constant) uniform Push { mat4 viewProj; uint drawIndex; };
layout(location = 0) out vec3 worldNormal;
void main() {
  mat4 model = draws[drawIndex].model;
  worldNormal = mat3(transpose(inverse(model))) * inNormal;
  gl_Position = viewProj * model * vec4(inPosition, 1.0);
}
