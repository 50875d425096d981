// What one voxel a triangle overlaps appends to its entity's fragment range: the material at the voxel
// centre's projection onto the triangle (textures when the variant reads them), the normal, the
// emission. Shared by the raster voxelizer (voxelize.frag) and the compute one for small triangles
// (voxelize_small.comp), so both write the same fragments. The includer declares `fragments`,
// `counters`, the four material textures and the specialization constants kBaseColorTexture,
// kEmissiveTexture, kMetallicRoughnessTexture, kAlphaMask and kNormalTexture.
#ifndef DYNGI_VOXEL_FRAGMENT_GLSL
#define DYNGI_VOXEL_FRAGMENT_GLSL
#include "shared/normal_map.h"

const float kVoxelTouchEps = 1e-4;  // voxel units: touching counts as overlapping, so nothing is missed

// The triangle in voxel units as both voxelizers see it.
struct VoxelTriangle {
  vec3 v0, v1, v2;
  vec2 uv0, uv1, uv2;
  vec3 n0, n1, n2;  // with a normal texture: the vertices' normals and tangents
  vec4 t0, t1, t2;
  vec4 albedo;      // rgb base colour factor, a metallic factor
  vec4 emission;    // rgb emitted radiance, a the alpha mask's threshold
  uvec4 range;      // first slot, capacity, counter of the entity's range; w the normal scale's bits
};

uint packEmission(vec3 e) {
  float m = max(e.r, max(e.g, e.b));
  if (m <= 0.0) return 0u;
  int k = clamp(int(ceil(log2(m))), -8, 23);
  vec3 s = clamp(e / exp2(float(k)), 0.0, 1.0);
  return packUnorm4x8(vec4(s, float(k + 8) / 255.0));
}

// Appends the fragment of voxel `v`, which the triangle overlaps; `nrm` is its unit face normal.
void appendVoxelFragment(ivec3 v, VoxelTriangle t, vec3 nrm) {
  vec3 center = vec3(v) + 0.5;
  vec4 albedo = vec4(t.albedo.rgb, 1.0);
  float metallic = t.albedo.a;
  vec3 emission = t.emission.rgb;
  float alpha = 1.0;
  vec3 normal = nrm;
  if (kBaseColorTexture || kEmissiveTexture || kMetallicRoughnessTexture || kNormalTexture) {
    // Barycentrics of the voxel centre's projection onto the triangle (clamped) for texturing.
    vec3 p = center - dot(center - t.v0, nrm) * nrm;
    vec3 e0 = t.v1 - t.v0, e1 = t.v2 - t.v0, ep = p - t.v0;
    float d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1), d20 = dot(ep, e0), d21 = dot(ep, e1);
    float den = d00 * d11 - d01 * d01;
    float bv = den != 0.0 ? (d11 * d20 - d01 * d21) / den : 0.0;
    float bw = den != 0.0 ? (d00 * d21 - d01 * d20) / den : 0.0;
    vec3 bary = clamp(vec3(1.0 - bv - bw, bv, bw), 0.0, 1.0);
    bary /= max(bary.x + bary.y + bary.z, 1e-6);
    vec2 uv = bary.x * t.uv0 + bary.y * t.uv1 + bary.z * t.uv2;
    if (kBaseColorTexture) {
      vec4 texel = textureLod(baseColorTex, uv, 0.0);
      albedo.rgb *= texel.rgb;
      alpha = texel.a;
    }
    if (kEmissiveTexture) emission *= textureLod(emissiveTex, uv, 0.0).rgb;
    if (kMetallicRoughnessTexture) metallic *= textureLod(metallicRoughnessTex, uv, 0.0).b;
    if (kNormalTexture) {
      // The shading normal at the voxel centre's projection, kept on the face normal's side (the side
      // the fragments' normals are averaged on); the voxel's normal is then the mean of its fragments'.
      vec3 ns = normalize(bary.x * t.n0 + bary.y * t.n1 + bary.z * t.n2);
      vec4 tangent = vec4(bary.x * t.t0.xyz + bary.y * t.t1.xyz + bary.z * t.t2.xyz, t.t0.w);
      normal = perturbNormal(ns, tangent, textureLod(normalTex, uv, 0.0).rgb, uintBitsToFloat(t.range.w));
      if (dot(ns, nrm) < 0.0) normal = -normal;
    }
  }
  if (kAlphaMask && alpha < t.emission.a) return;  // cut out at the voxel's centre
  albedo.rgb *= 1.0 - metallic;  // the diffuse share
  uint slot = atomicAdd(counters[t.range.z], 1u);
  if (slot >= t.range.y) return;  // over capacity: counted, so the host grows the range
  uint coord = uint(v.x) | (uint(v.y) << 10) | (uint(v.z) << 20);
  fragments[t.range.x + slot] = uvec4(coord, packUnorm4x8(albedo), packSnorm4x8(vec4(normal, 0.0)), packEmission(emission));
}

#endif
