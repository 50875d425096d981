#version 460
// The host's lighting: emission, direct light from every light (glTF's units and falloffs, no shadows),
// and dyngi's indirect light: albedo x (1 - metallic) x E/pi plus the specular colour x specular.
layout(local_size_x = 8, local_size_y = 8) in;
struct Light {
  vec4 positionType;     // xyz, w 0 directional, 1 point, 2 spot
  vec4 directionRange;   // xyz where it shines, w range (0: none)
  vec4 radiance;         // rgb colour x intensity
  vec4 cones;            // x cos inner, y cos outer
};
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1) uniform sampler2D normals;
layout(set = 0, binding = 2) uniform sampler2D baseColor;
layout(set = 0, binding = 3) uniform sampler2D material;
layout(set = 0, binding = 4) uniform sampler2D emissive;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D giIndirect;
layout(set = 0, binding = 6, rgba32f) uniform readonly image2D giSpecular;
layout(set = 0, binding = 7) readonly buffer Lights { Light lights[]; };
layout(set = 0, binding = 8, rgba32f) uniform writeonly image2D outHdr;
layout(set = 0, binding = 9, rgba8) uniform writeonly image2D outDisplay;  // tone-mapped, sRGB-encoded
layout(push_constant) uniform Push { mat4 invViewProj; vec4 cameraPos; uvec4 sizeAndLights; };

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

// The PNG's mapping (main.cpp, writePng): a filmic curve, then sRGB.
vec3 display(vec3 hdr) {
  vec3 x = max(hdr, vec3(0.0));
  vec3 mapped = clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  return mix(12.92 * mapped, 1.055 * pow(mapped, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), mapped));
}

void store(ivec2 px, vec3 colour) {
  imageStore(outHdr, px, vec4(colour, 1.0));
  imageStore(outDisplay, px, vec4(display(colour), 1.0));
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  uvec2 size = sizeAndLights.xy;
  if (px.x >= int(size.x) || px.y >= int(size.y)) return;
  float d = texelFetch(depth, px, 0).r;
  if (d <= 0.0) {  // reversed Z: nothing hit
    store(px, vec3(0.0));
    return;
  }
  vec2 ndc = (vec2(px) + 0.5) / vec2(size) * 2.0 - 1.0;
  vec4 p = invViewProj * vec4(ndc, d, 1.0);
  vec3 position = p.xyz / p.w;
  vec3 n = octahedralDecode(texelFetch(normals, px, 0).xy);
  vec4 base = texelFetch(baseColor, px, 0);
  float metallic = texelFetch(material, px, 0).g;
  vec3 albedo = base.rgb * (1.0 - metallic);
  vec3 colour = texelFetch(emissive, px, 0).rgb;
  for (uint i = 0u; i < sizeAndLights.z; ++i) {
    Light l = lights[i];
    vec3 toLight;
    float falloff = 1.0;
    if (l.positionType.w == 0.0) {
      toLight = -l.directionRange.xyz;
    } else {
      vec3 v = l.positionType.xyz - position;
      float dist2 = max(dot(v, v), 1e-8);
      toLight = v / sqrt(dist2);
      falloff = 1.0 / dist2;
      if (l.directionRange.w > 0.0) {
        float r = sqrt(dist2) / l.directionRange.w;
        falloff *= pow(clamp(1.0 - r * r * r * r, 0.0, 1.0), 2.0);
      }
      if (l.positionType.w == 2.0) {
        float c = dot(-toLight, l.directionRange.xyz);
        float t = clamp((c - l.cones.y) / max(l.cones.x - l.cones.y, 1e-4), 0.0, 1.0);
        falloff *= t * t;
      }
    }
    colour += albedo / 3.14159265 * l.radiance.rgb * falloff * max(dot(n, toLight), 0.0);
  }
  vec3 specularColour = mix(vec3(0.04), base.rgb, metallic);
  colour += albedo * imageLoad(giIndirect, px).rgb + specularColour * imageLoad(giSpecular, px).rgb;
  store(px, colour);
}
