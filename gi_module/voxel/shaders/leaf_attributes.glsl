// Voxel attributes: the leaf sums svo_leaf_attributes.comp makes (DYNGI_LEAF_* in gi_gpu_types.h) and the
// voxel attributes image they end in (DYNGI_SVO_VOXEL_ATTRIBUTES in gi_gpu_types.h): the one encoder and
// decoder of both (C++ twin for the tests: VoxelProbe::checkLeafAttributes). Readers of an occupied
// voxel's attributes declare `uimage3D voxelAttributes` (rgba32ui) and call voxelAttributesAt(voxel); the
// passes that write the image declare `uvec4 sums[]` (the leaf sums) too.
#ifndef DYNGI_LEAF_ATTRIBUTES_GLSL
#define DYNGI_LEAF_ATTRIBUTES_GLSL

struct LeafAttributes {
  uint count;        // fragments in the voxel (up to 255); 0: none
  vec3 albedo;
  vec3 normalSum;    // mean of the fragments' unit normals: short where they disagree (both sides of a thin wall)
  vec3 emission;     // mean over the emitting fragments
};

// Sums over some of a voxel's fragments: `summed` of them for the albedo and the normal, `emitters` for
// the emission.
struct LeafSums {
  uint count;
  float summed;
  vec3 albedo;
  vec3 normal;
  float emitters;
  vec3 emission;
};

// Sums as a texel of the voxel attributes image holds them (means and counts).
LeafSums unpackSums(uvec4 t) {
  LeafSums s;
  s.count = t.x >> 24;
  s.summed = float(s.count);
  s.albedo = unpackUnorm4x8(t.x).rgb * s.summed;
  s.normal = unpackSnorm4x8(t.y).xyz * s.summed;
  s.emitters = float(t.y >> 24);
  s.emission = vec3(unpackHalf2x16(t.z), unpackHalf2x16(t.w).x) * s.emitters;
  return s;
}

uvec4 packSums(LeafSums s) {
  float n = max(s.summed, 1.0);
  vec3 e = min(s.emission / max(s.emitters, 1.0), vec3(65000.0));
  return uvec4((packUnorm4x8(vec4(s.albedo / n, 0.0)) & 0xFFFFFFu) | (uint(min(s.summed, 255.0)) << 24),
               (packSnorm4x8(vec4(s.normal / n, 0.0)) & 0xFFFFFFu) | (uint(min(s.emitters, 255.0)) << 24), packHalf2x16(e.rg),
               packHalf2x16(vec2(e.b, 0.0)));
}

// The attributes of the occupied voxel at `voxel` (count 0: none there).
LeafAttributes voxelAttributesAt(ivec3 voxel) {
  LeafSums s = unpackSums(imageLoad(voxelAttributes, voxel));
  LeafAttributes a;
  a.count = s.count;
  a.albedo = s.albedo / max(s.summed, 1.0);
  a.normalSum = s.normal / max(s.summed, 1.0);
  a.emission = s.emission / max(s.emitters, 1.0);
  return a;
}

#ifdef DYNGI_LEAF_SUMS
// Leaf `leaf`'s sums from the attribute pass (two uvec4s: lavapipe pays per load, not per byte).
LeafSums leafSums(uint leaf) {
  uvec4 w = sums[2u * leaf];  // count, albedo rg, albedo b | normal x, normal yz
  uvec4 e = sums[2u * leaf + 1u];  // emission rgb, emitters
  LeafSums s;
  s.count = w[DYNGI_LEAF_COUNT];
  s.summed = float(min(s.count, DYNGI_LEAF_MAX_FRAGMENTS));
  uint rg = w[DYNGI_LEAF_ALBEDO_RG], bx = w[DYNGI_LEAF_ALBEDO_B_NORMAL_X], yz = w[DYNGI_LEAF_NORMAL_YZ];
  s.albedo = vec3(rg & 0xFFFFu, rg >> 16, bx & 0xFFFFu) / 255.0;
  s.normal = (vec3(bx >> 16, yz & 0xFFFFu, yz >> 16) - 127.0 * s.summed) / 127.0;
  s.emission = vec3(e[DYNGI_LEAF_EMISSION - 4u], e[DYNGI_LEAF_EMISSION - 3u], e[DYNGI_LEAF_EMISSION - 2u]) / DYNGI_LEAF_EMISSION_SCALE;
  s.emitters = float(e[DYNGI_LEAF_EMITTERS - 4u]);
  return s;
}
#endif

LeafSums addSums(LeafSums a, LeafSums b) {
  a.count += b.count;
  a.summed += b.summed;
  a.albedo += b.albedo;
  a.normal += b.normal;
  a.emitters += b.emitters;
  a.emission += b.emission;
  return a;
}

#endif
