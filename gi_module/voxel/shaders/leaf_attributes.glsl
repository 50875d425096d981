// A leaf's averaged attributes from svo_leaf_attributes.comp's sums (DYNGI_LEAF_* in gi_gpu_types.h):
// the one decoder every reader of the attribute buffer uses. The includer declares `uint attributes[]`,
// and may define DYNGI_LEAF_READ_EMISSION to a specialization constant that is false when no fragment emits
// (VoxelScene::fragmentsEmit): the emission words are then not read (lavapipe reads what a branch skips).
#ifndef DYNGI_LEAF_ATTRIBUTES_GLSL
#define DYNGI_LEAF_ATTRIBUTES_GLSL
#ifndef DYNGI_LEAF_READ_EMISSION
#define DYNGI_LEAF_READ_EMISSION true
#endif

struct LeafAttributes {
  uint count;        // fragments in the leaf; 0: none (an empty slot)
  vec3 albedo;
  vec3 normalSum;    // mean of the fragments' unit normals: short where they disagree (both sides of a thin wall)
  vec3 emission;     // mean over the emitting fragments
};

LeafAttributes leafAttributes(uint leaf) {
  uint base = leaf * DYNGI_LEAF_ATTRIBUTE_INTS;
  LeafAttributes a;
  a.count = attributes[base + DYNGI_LEAF_COUNT];
  float summed = float(clamp(a.count, 1u, DYNGI_LEAF_MAX_FRAGMENTS));
  uint rg = attributes[base + DYNGI_LEAF_ALBEDO_RG], bx = attributes[base + DYNGI_LEAF_ALBEDO_B_NORMAL_X],
       yz = attributes[base + DYNGI_LEAF_NORMAL_YZ];
  a.albedo = vec3(rg & 0xFFFFu, rg >> 16, bx & 0xFFFFu) / (255.0 * summed);
  a.normalSum = (vec3(bx >> 16, yz & 0xFFFFu, yz >> 16) / summed - 127.0) / 127.0;
  a.emission = vec3(0.0);
  if (DYNGI_LEAF_READ_EMISSION) {
    uint e = base + DYNGI_LEAF_EMISSION;
    a.emission = vec3(attributes[e], attributes[e + 1u], attributes[e + 2u]) /
                 (DYNGI_LEAF_EMISSION_SCALE * max(float(attributes[base + DYNGI_LEAF_EMITTERS]), 1.0));
  }
  return a;
}

#endif
