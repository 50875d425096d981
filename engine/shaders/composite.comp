#version 460
// final radiance = direct + albedo * indirect. `indirect` holds diffuse-reflected incident light
// per unit albedo (E_indirect / pi); it is zero when no GI feature wrote it.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D direct;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = 2) uniform sampler2D gAlbedo;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D outHdr;
layout(push_constant) uniform Push { uvec2 size; };
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= int(size.x) || px.y >= int(size.y)) return;
  vec4 albedo = texelFetch(gAlbedo, px, 0);
  vec3 c = imageLoad(direct, px).rgb + albedo.rgb * (1.0 - albedo.a) * imageLoad(indirect, px).rgb;
  imageStore(outHdr, px, vec4(c, 1.0));
}
