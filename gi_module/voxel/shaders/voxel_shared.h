// The voxel scene's C++/GLSL layouts: the SVO node word, the voxelization draw, the SVO build's
// bookkeeping and bindings, the leaf list and the voxel attributes (gi_module/voxel/).
#ifndef DYNGI_VOXEL_SHARED_H
#define DYNGI_VOXEL_SHARED_H

#include "shared/gi_gpu_types.h"

DYNGI_GPU_NAMESPACE_BEGIN

// SVO node word: bit 31 = occupied / subdivided; bits 0..30 = child group (0: none yet). Children of a
// node with group g are pool entries 8g .. 8g+7 (group 0 is the root's own group, so g >= 1).
#define DYNGI_SVO_FLAG 0x80000000u
#define DYNGI_SVO_GROUP_MASK 0x7FFFFFFFu
#define DYNGI_SVO_MAX_LEVELS 10
// A voxel fragment whose coord word is this is empty (ranges are filled with it before voxelizing).
#define DYNGI_VOXEL_EMPTY 0xFFFFFFFFu
#define DYNGI_VOXEL_COORD_BITS 10

// Push constants of the voxelization draw (one batch of instances: each reads its transform and material
// from the frame's draw records and its fragment range from VoxelizeRange, both at its slot).
#ifdef __cplusplus
struct alignas(16) VoxelizePush {
#else
struct VoxelizePush {
#endif
  mat4 worldToVoxel;    // world -> voxel units ([0, resolution)^3)
  uint resolution;      // voxels per side
  uint firstInstance;   // the compute voxelizer's batch: its first FrameInstances slot,
  uint instanceCount;   // its instances
  uint triangleCount;   // and its mesh's triangles
};
// An instance's fragment range (storage buffer, at its FrameInstances slot).
#ifdef __cplusplus
struct alignas(16) VoxelizeRange {
#else
struct VoxelizeRange {
#endif
  uint firstSlot;       // first slot of the entity's range,
  uint capacity;        // its size,
  uint counterIndex;    // and the counter its fragments are appended with
  uint pad0;
};

// Per-level bookkeeping of the SVO build (storage buffer, one per level).
#ifdef __cplusplus
struct alignas(16) SvoLevel {
#else
struct SvoLevel {
#endif
  uvec4 range;          // x first node, y node count, z groups allocated before this level's expand, w unused
  uvec4 dispatch;       // indirect dispatch args for this level's expand pass (x groups, 1, 1)
};

// SVO build passes over fragments and nodes run 64-wide workgroups in which each invocation takes
// this many items (grid-stride): lavapipe pays a fixed cost per invocation that dwarfs one step.
#define DYNGI_SVO_ITEMS_PER_INVOCATION 16u
// The build's occupancy pyramid: one bit per cell of every level 0..depth, each level in Morton order
// (x in the lowest bit of each triple, the SVO's child order) and starting on a byte: level l at bit
// DYNGI_SVO_LEVEL_BASE(l) (0, 8, 16, 80, 592, ...), cell with Morton code m at base + m. A node's 8
// children are then the aligned byte at base(l + 1) + 8m: svo_expand.comp reads them in one load
// (eight scattered bit reads before). svo_mark.comp marks it.
#define DYNGI_SVO_LEVEL_BASE(l) ((l) == 0u ? 0u : 8u + 8u * (((1u << (3u * ((l) - 1u))) - 1u) / 7u))

// Global SVO counters.
#ifdef __cplusplus
struct alignas(16) SvoCounters {
#else
struct SvoCounters {
#endif
  uvec4 groups;         // x groups allocated (incl. root group), y group capacity, z overflowed (0/1), w leaves
};

// svo_expand
#define DYNGI_SVO_EXPAND_BINDING_NODES 0
#define DYNGI_SVO_EXPAND_BINDING_NODE_CELLS 1
#define DYNGI_SVO_EXPAND_BINDING_OCCUPANCY 2
#define DYNGI_SVO_EXPAND_BINDING_LEVELS 3
#define DYNGI_SVO_EXPAND_BINDING_COUNTERS 4
#define DYNGI_SVO_EXPAND_BINDING_LEAF_LIST 5
// The occupied leaves, compacted (svo_expand.comp appends each leaf): a header of
// DYNGI_SVO_LEAF_LIST_HEADER uints (indirect dispatch args x, 1, 1 for passes taking
// DYNGI_SVO_ITEMS_PER_INVOCATION leaves per invocation in 64-wide groups, then the count; written by
// svo_level.comp at the leaf level), then DYNGI_SVO_LEAF_ENTRY_UINTS uints an entry: the leaf's node
// index and its cell's Morton code (a reader needs no load from the node cells). Passes over leaves walk
// it instead of the leaf level's slots, half of which are empty siblings on surfaces. Readers declare it
// `{ uvec4 header; uvec2 entries[]; }`.
#define DYNGI_SVO_LEAF_LIST_HEADER 4u
#define DYNGI_SVO_LEAF_ENTRY_UINTS 2u
// svo_leaf_attributes. A leaf's attributes are DYNGI_LEAF_ATTRIBUTE_INTS uints at leaf * that, sums over
// its first DYNGI_LEAF_MAX_FRAGMENTS fragments (integer atomics; voxel/shaders/leaf_attributes.glsl
// averages them): the fragment count (all of them), the albedo 0..255 per channel and the normal
// x 127 + 127 per axis, two 16-bit sums to a uint (under 65536 for 256 fragments: four atomics a
// fragment where there were eight), the emitted radiance x 256 per channel and the count of emitting
// fragments (emission is their mean: a light panel on a ceiling shares its voxels with the ceiling, and a
// mean over both would halve it), added by emitting fragments only. Only the moving entities' fragments
// are summed in most builds: the static ones' are kept per voxel (DYNGI_SVO_VOXEL_ATTRIBUTES below).
#define DYNGI_LEAF_ATTRIBUTE_INTS 8u
#define DYNGI_LEAF_COUNT 0u
#define DYNGI_LEAF_ALBEDO_RG 1u
#define DYNGI_LEAF_ALBEDO_B_NORMAL_X 2u
#define DYNGI_LEAF_NORMAL_YZ 3u
#define DYNGI_LEAF_EMISSION 4u
#define DYNGI_LEAF_EMITTERS 7u
#define DYNGI_LEAF_MAX_FRAGMENTS 256u
#define DYNGI_LEAF_EMISSION_SCALE 256.0
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_FRAGMENTS 0
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_NODES 1
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_LEVELS 2
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_ATTRIBUTES 3
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_CHUNKS 4  /* the mark pass' chunks: one per workgroup */
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_MOVING 5  /* the moving leaves' list (DYNGI_SVO_VOXEL_ATTRIBUTES) */
#define DYNGI_SVO_LEAF_ATTRIBUTES_BINDING_COUNTERS 6  /* the voxelizer's fragment counters (DYNGI_SVO_CHUNK) */
// The voxel attributes: each occupied voxel's mean albedo, normal and emission, an rgba32ui 3D image over
// the volume (an image load costs lavapipe less than storage-buffer ones; the passes over leaves read
// one texel a leaf). x: the mean albedo in unorm bytes 0-2 and the fragments it averages (up to 255) in
// byte 3; y: the mean of the unit normals in snorm bytes 0-2 and the emitting fragments (up to 255) in
// byte 3; z, w: their mean emission as halves (r, g) (b, 0). svo_voxel_attributes.comp writes it from the
// leaf sums (above), in steps (DYNGI_VOXEL_ATTRIBUTES_STEP_*): the static entities' (SvoBuilder's static
// set, as for the kept occupancy pyramid) when that set changes; then in every build the moving
// entities' sums added to their voxels, after the voxels the last build's moving leaves touched got
// back what they held before it. So a build sums only the moving entities' fragments, and the leaf sums
// are scratch: zero again once read.
#define DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEAF_LIST 0
#define DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_LEVELS 1
#define DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_SUMS 2
#define DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_VOXELS 3
#define DYNGI_SVO_VOXEL_ATTRIBUTES_BINDING_MOVING 4
#define DYNGI_VOXEL_ATTRIBUTES_STEP_STATIC 0   /* over the SVO's leaf list: the static entities' sums into their voxels */
#define DYNGI_VOXEL_ATTRIBUTES_STEP_RESTORE 1  /* over the last build's moving leaves: their voxels as before it */
#define DYNGI_VOXEL_ATTRIBUTES_STEP_ARGS 2     /* one invocation: the moving leaves' dispatch from their count */
#define DYNGI_VOXEL_ATTRIBUTES_STEP_MERGE 3    /* over this build's moving leaves: their sums added to their voxels */
// The moving leaves (svo_leaf_attributes.comp appends a leaf at its first fragment): a header uvec4
// (indirect dispatch x, 1, 1 for 64 entries a group; count), then 2 uvec4 an entry: (leaf slot, its cell's
// Morton code, 0, 0) and the voxel's texel before the merge.
// svo_level
#define DYNGI_SVO_LEVEL_BINDING_LEVELS 0
#define DYNGI_SVO_LEVEL_BINDING_COUNTERS 1
#define DYNGI_SVO_LEVEL_BINDING_NODES 2
#define DYNGI_SVO_LEVEL_BINDING_NODE_CELLS 3
#define DYNGI_SVO_LEVEL_BINDING_OCCUPANCY 4
#define DYNGI_SVO_LEVEL_BINDING_LEAF_LIST 5
// svo_march
#define DYNGI_SVO_MARCH_BINDING_NODES 0
#define DYNGI_SVO_MARCH_BINDING_SEGMENTS 1
#define DYNGI_SVO_MARCH_BINDING_RESULTS 2
// svo_mark
#define DYNGI_SVO_MARK_BINDING_FRAGMENTS 0
#define DYNGI_SVO_MARK_BINDING_OCCUPANCY 1
#define DYNGI_SVO_MARK_BINDING_CHUNKS 2
#define DYNGI_SVO_MARK_BINDING_COUNTERS 3
// A chunk of fragment slots, one a workgroup of svo_mark.comp and svo_leaf_attributes.comp (SvoBuilder::plan
// cuts them from the entity ranges), a uvec4: x its first slot, y its end, z the first slot of its
// entity's range, w that range's fragment counter (the voxelizer's). The voxelizer appends, so a range's
// fragments are its first counters[w] slots: the chunk's fragments end at DYNGI_SVO_CHUNK_END. A moving
// range holds slack for its count to grow (about twice it), slots every pass over them paid for. A chunk
// of several small neighbouring ranges has w DYNGI_SVO_CHUNK_NO_COUNTER and ends at y: the slots past a
// range's fragments are empty (DYNGI_VOXEL_EMPTY, filled before each voxelization), and are skipped.
#define DYNGI_SVO_CHUNK_NO_COUNTER 0xFFFFFFFFu
#define DYNGI_SVO_CHUNK_END(chunk, counters) \
  ((chunk).w == DYNGI_SVO_CHUNK_NO_COUNTER ? (chunk).y : min((chunk).y, (chunk).z + (counters)[(chunk).w]))
// voxel_debug
#define DYNGI_VOXEL_DEBUG_BINDING_FRAME 0
#define DYNGI_VOXEL_DEBUG_BINDING_NODES 1
#define DYNGI_VOXEL_DEBUG_BINDING_OUT_HDR 2
#define DYNGI_VOXEL_DEBUG_BINDING_NODE_CELLS 3
#define DYNGI_VOXEL_DEBUG_BINDING_VOXEL_ATTRIBUTES 4
// voxelize
#define DYNGI_VOXELIZE_BINDING_FRAGMENTS 0
#define DYNGI_VOXELIZE_BINDING_COUNTERS 1
#define DYNGI_VOXELIZE_BINDING_BASE_COLOR_TEX 2
#define DYNGI_VOXELIZE_BINDING_EMISSIVE_TEX 3
#define DYNGI_VOXELIZE_BINDING_METALLIC_ROUGHNESS_TEX 4
#define DYNGI_VOXELIZE_BINDING_NORMAL_TEX 5
#define DYNGI_VOXELIZE_BINDING_INSTANCES 6
#define DYNGI_VOXELIZE_BINDING_RANGES 7
#define DYNGI_VOXELIZE_BINDING_VERTICES 8  // the compute voxelizer's mesh (voxelize_small.comp)
#define DYNGI_VOXELIZE_BINDING_INDICES 9


#define DYNGI_SVO_MARK_PUSH uint firstChunk; uint depth;
#define DYNGI_SVO_LEVEL_PUSH uint level; uint depth; /* the leaf level */
#define DYNGI_SVO_EXPAND_PUSH uint level; uint depth; uint writeLeafList; /* 0: leaves counted, not listed (nothing walks the list) */
#define DYNGI_SVO_LEAF_ATTRIBUTES_PUSH uint depth; uint leafCapacity; uint firstChunk; uint listLeaves; /* 1: append each leaf to the moving leaves */
#define DYNGI_SVO_VOXEL_ATTRIBUTES_PUSH uint depth; uint leafCapacity;
#define DYNGI_SVO_MARCH_PUSH                                                         \
  vec4 worldToVoxel; /* xyz origin, w 1 / voxel size */                            \
  uint count;                                                                      \
  uint depth;                                                                      \
  float res;                                                                       \
  float eps;         /* voxel units */
#define DYNGI_VOXEL_DEBUG_PUSH                                                       \
  vec4 worldToVoxel; /* xyz origin, w 1 / voxel size */                            \
  uint depth;                                                                      \
  float res;                                                                       \
  uint mode;         /* 0 voxels, 1 svo-steps */

#ifdef __cplusplus
struct SvoMarkPush { DYNGI_SVO_MARK_PUSH };
struct SvoLevelPush { DYNGI_SVO_LEVEL_PUSH };
struct SvoExpandPush { DYNGI_SVO_EXPAND_PUSH };
struct SvoLeafAttributesPush { DYNGI_SVO_LEAF_ATTRIBUTES_PUSH };
struct SvoVoxelAttributesPush { DYNGI_SVO_VOXEL_ATTRIBUTES_PUSH };
struct SvoMarchPush { DYNGI_SVO_MARCH_PUSH };
struct VoxelDebugPush { DYNGI_VOXEL_DEBUG_PUSH };

static_assert(sizeof(VoxelizePush) == 80 && offsetof(VoxelizePush, resolution) == 64);
static_assert(sizeof(VoxelizeRange) == 16);
static_assert(sizeof(SvoLevel) == 32 && offsetof(SvoLevel, dispatch) == 16);
static_assert(sizeof(SvoCounters) == 16);
static_assert(sizeof(SvoMarkPush) == 8 && sizeof(SvoLevelPush) == 8 && sizeof(SvoExpandPush) == 12);
static_assert(sizeof(SvoLeafAttributesPush) == 16 && offsetof(SvoLeafAttributesPush, listLeaves) == 12);
static_assert(sizeof(SvoVoxelAttributesPush) == 8);
static_assert(sizeof(SvoMarchPush) == 32 && offsetof(SvoMarchPush, count) == 16 && offsetof(SvoMarchPush, eps) == 28);
static_assert(sizeof(VoxelDebugPush) == 28 && offsetof(VoxelDebugPush, mode) == 24);
#endif

DYNGI_GPU_NAMESPACE_END

#endif
