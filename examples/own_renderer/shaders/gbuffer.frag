#version 460
// Octahedral world normals in RG16F, base colour and metallic in RGBA8, roughness and metallic in a
// second RGBA8, emission in RGBA16F.
struct Draw {
  mat4 model;
  vec4 baseColor;
  vec4 emissiveRoughness;
};
layout(set = 0, binding = 0) readonly buffer Draws { Draw draws[]; };
layout(push_constant) uniform Push { mat4 viewProj; uint drawIndex; };
layout(location = 0) in vec3 worldNormal;
layout(location = 0) out vec2 outNormal;
layout(location = 1) out vec4 outBaseColor;
layout(location = 2) out vec4 outMaterial;
layout(location = 3) out vec4 outEmissive;

vec2 octahedralEncode(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return n.xy;
}

void main() {
  Draw d = draws[drawIndex];
  vec3 n = normalize(worldNormal);
  if (!gl_FrontFacing) n = -n;
  outNormal = octahedralEncode(n);
  outBaseColor = vec4(d.baseColor.rgb, d.baseColor.a);
  outMaterial = vec4(d.emissiveRoughness.a, d.baseColor.a, 0.0, 0.0);
  outEmissive = vec4(d.emissiveRoughness.rgb, 0.0);
}
