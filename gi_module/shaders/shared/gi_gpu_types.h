// Struct layouts and constants shared by the GI module's C++ and GLSL (the engine's live in
// engine/shaders/shared/gpu_types.h). 16-byte members only, so std140/std430 and C++ agree.
#ifndef DYNGI_GI_GPU_TYPES_H
#define DYNGI_GI_GPU_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gi::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using mat3x4 = glm::mat3x4;
#endif

// SVO node word: bit 31 = occupied / subdivided; bits 0..30 = child group (0: none yet). Children of a
// node with group g are pool entries 8g .. 8g+7 (group 0 is the root's own group, so g >= 1).
#define DYNGI_SVO_FLAG 0x80000000u
#define DYNGI_SVO_GROUP_MASK 0x7FFFFFFFu
#define DYNGI_SVO_MAX_LEVELS 10
// A voxel fragment whose coord word is this is empty (ranges are filled with it before voxelizing).
#define DYNGI_VOXEL_EMPTY 0xFFFFFFFFu
#define DYNGI_VOXEL_COORD_BITS 10

// Push constants of the voxelization draw (<= 128 bytes).
#ifdef __cplusplus
struct alignas(16) VoxelizePush {
#else
struct VoxelizePush {
#endif
  mat3x4 modelToVoxelRows;  // object space -> voxel units ([0, resolution)^3): the affine map's three rows
  uint firstSlot;       // the entity's fragment range: first slot,
  uint capacity;        // its size,
  uint counterIndex;    // and the counter its fragments are appended with
  uint resolution;      // voxels per side
  vec4 albedo;          // rgb base colour factor, a metallic factor (diffuse = base x (1 - metallic))
  vec4 emission;        // rgb emitted radiance (a unused)
  vec4 uvLinear;        // KHR_texture_transform (engine/shaders/shared/uv_transform.h): the linear map,
  vec4 uvOffset;        // and in xy the offset; z the alpha mask's threshold (alphaMaskThreshold()), w the normal scale
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

// A virtual point light: a point on a surface that reflects `flux` (watts, reflected: rho * E * A)
// with a cosine lobe around `normal`.
#ifdef __cplusplus
struct alignas(16) GpuVpl {
#else
struct GpuVpl {
#endif
  vec4 position;        // xyz world, w bounce (0: lit directly by a light), negative: invalid
  vec4 normal;          // xyz unit normal, w path index
  vec4 flux;            // rgb reflected flux, w luminance (for skipping dim VPLs)
};

// One layer of the reflective shadow maps (storage buffer): how light `light` sees the scene.
#ifdef __cplusplus
struct alignas(16) RsmLayer {
#else
struct RsmLayer {
#endif
  mat4 viewProj;
  vec4 axis;            // xyz view forward, w texel footprint (perspective: per unit distance; ortho: world side)
  uint lightIndex;
  uint orthographic;    // 0/1
  uint resolution;      // RSM texels per side
  uint pad0;
};

// Push constants of the RSM draw.
#ifdef __cplusplus
struct alignas(16) RsmPush {
#else
struct RsmPush {
#endif
  mat4 model;
  vec4 baseColor;       // rgb linear base colour factor, a metallic factor (diffuse = base x (1 - metallic))
  vec4 uvLinear;        // KHR_texture_transform (engine/shaders/shared/uv_transform.h): the linear map,
  vec4 uvOffset;        // and in xy the offset; z the alpha mask's threshold (alphaMaskThreshold()), w the normal scale
  uint layer;           // the RsmLayer drawn
  uint pad0, pad1, pad2;
};

// Descriptor bindings of the GI module's passes (set 0, push descriptors): the shaders declare them and
// the C++ binds them by these names (the shared gather's are above, with its technique variants').
// filter
#define DYNGI_FILTER_BINDING_FRAME 0
#define DYNGI_FILTER_BINDING_FILTER_INPUT 1
#define DYNGI_FILTER_BINDING_OUT_INDIRECT 2  // filter_columns
#define DYNGI_FILTER_BINDING_OUT_ROWS 3      // filter_rows: the packed intermediate
// compensate (the distance clamp's lost light: compensate.comp traces it between the merge filter's
// passes, filter_columns.comp adds it)
#define DYNGI_COMPENSATE_BINDING_FRAME 0
#define DYNGI_COMPENSATE_BINDING_POSITION 1
#define DYNGI_COMPENSATE_BINDING_NORMAL 2
#define DYNGI_COMPENSATE_BINDING_ALBEDO 3
#define DYNGI_COMPENSATE_BINDING_EMISSIVE 4
#define DYNGI_COMPENSATE_BINDING_ROWS 5             // the merge filter's rows pass: the indirect light where a ray lands
#define DYNGI_COMPENSATE_BINDING_LIGHTS 6
#define DYNGI_COMPENSATE_BINDING_SHADOW_MATRICES 7
#define DYNGI_COMPENSATE_BINDING_SHADOW_MAPS 8
#define DYNGI_COMPENSATE_BINDING_OUT 9              // one texel per DYNGI_COMPENSATE_SCALE^2 pixels, packed as filter_input.glsl
#define DYNGI_COMPENSATE_BINDING_TRACED 10          // compensate_blur: compensate.comp's output
#define DYNGI_FILTER_BINDING_COMPENSATION 4         // filter_columns: that image, read
#define DYNGI_COMPENSATE_SCALE 4                    // the compensation is traced for one pixel in 4 x 4
// many_lights_debug
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_FRAME 0
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_G_ALBEDO 1
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_INDIRECT 2
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_RAW 3
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_VPLS 4
#define DYNGI_MANY_LIGHTS_DEBUG_BINDING_HDR 5
// rsm
#define DYNGI_RSM_BINDING_LAYERS 0
#define DYNGI_RSM_BINDING_LIGHTS 1
#define DYNGI_RSM_BINDING_BASE_COLOR_TEX 2
#define DYNGI_RSM_BINDING_METALLIC_ROUGHNESS_TEX 3
#define DYNGI_RSM_BINDING_NORMAL_TEX 4
// vpl_bounce
#define DYNGI_VPL_BOUNCE_BINDING_VPLS 0
#define DYNGI_VPL_BOUNCE_BINDING_NODES 1
#define DYNGI_VPL_BOUNCE_BINDING_NODE_CELLS 2
#define DYNGI_VPL_BOUNCE_BINDING_VOXEL_ATTRIBUTES 3
// vpl_tail
#define DYNGI_VPL_TAIL_BINDING_VPLS 0
// vpl_cdf_rows
#define DYNGI_VPL_CDF_ROWS_BINDING_RSM_FLUX 0
#define DYNGI_VPL_CDF_ROWS_BINDING_ROW_PREFIX 1
#define DYNGI_VPL_CDF_ROWS_BINDING_ROW_SUMS 2
// vpl_cdf_total
#define DYNGI_VPL_CDF_TOTAL_BINDING_ROW_SUMS 0
// vpl_sample
#define DYNGI_VPL_SAMPLE_BINDING_RSM_POSITION 0
#define DYNGI_VPL_SAMPLE_BINDING_RSM_NORMAL 1
#define DYNGI_VPL_SAMPLE_BINDING_RSM_FLUX 2
#define DYNGI_VPL_SAMPLE_BINDING_ROW_PREFIX 3
#define DYNGI_VPL_SAMPLE_BINDING_ROW_CDF 4
#define DYNGI_VPL_SAMPLE_BINDING_VPLS 5
// temporal_reproject
#define DYNGI_TEMPORAL_REPROJECT_BINDING_FRAME 0
#define DYNGI_TEMPORAL_REPROJECT_BINDING_SET_SAMPLES 1
#define DYNGI_TEMPORAL_REPROJECT_BINDING_CAMERAS 2
#define DYNGI_TEMPORAL_REPROJECT_BINDING_SUMS 3
#define DYNGI_TEMPORAL_REPROJECT_BINDING_FILTER_INPUT 4
#define DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE 5
#define DYNGI_TEMPORAL_REPROJECT_BINDING_QUEUE_ARGS 6
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
// range holds slack for its count to grow (about twice it), slots every pass over them paid for.
#define DYNGI_SVO_CHUNK_END(chunk, counters) min((chunk).y, (chunk).z + (counters)[(chunk).w])
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

// Voxel cone tracing (techniques/vct/): the passes over the occupied voxels (SVO leaves) and the screen.
// vct_inject: direct light and emission of each occupied voxel into the radiance volume
#define DYNGI_VCT_INJECT_BINDING_LEAF_LIST 0  /* the SVO's compacted leaf list */
#define DYNGI_VCT_INJECT_BINDING_VOXEL_ATTRIBUTES 1
#define DYNGI_VCT_INJECT_BINDING_LIGHTS 2
#define DYNGI_VCT_INJECT_BINDING_SHADOW_MATRICES 3
#define DYNGI_VCT_INJECT_BINDING_SHADOW_MAPS 4
#define DYNGI_VCT_INJECT_BINDING_DIRECT 5  /* read (last frame's, the temporal blend's history) and written in place */
#define DYNGI_VCT_INJECT_BINDING_RADIANCE 6
// vct_clear_stale: the per-voxel state of the cells that emptied since the last SVO build, zeroed
#define DYNGI_VCT_CLEAR_BINDING_RUNS 0              /* uvec2 (SVO level, first Morton code) per run of 32 cells */
#define DYNGI_VCT_CLEAR_BINDING_PREVIOUS_OCCUPANCY 1  /* the build before's pyramid */
#define DYNGI_VCT_CLEAR_BINDING_OCCUPANCY 2           /* the last build's */
#define DYNGI_VCT_CLEAR_BINDING_RADIANCE 3            /* level 0 */
#define DYNGI_VCT_CLEAR_BINDING_DIRECT 4
#define DYNGI_VCT_CLEAR_BINDING_ATLAS 5               /* the anisotropic atlas' level 0 (anisotropic only) */
#define DYNGI_VCT_CLEAR_BINDING_ATLAS_1 6             /* its level 1 */
// vct_bounce: one more bounce per occupied voxel (cones over the radiance volume), then vct_commit
#define DYNGI_VCT_BOUNCE_BINDING_LEAF_LIST 0  /* the SVO's compacted leaf list */
#define DYNGI_VCT_BOUNCE_BINDING_VOXEL_ATTRIBUTES 1
#define DYNGI_VCT_BOUNCE_BINDING_DIRECT 2
#define DYNGI_VCT_BOUNCE_BINDING_RADIANCE 3
#define DYNGI_VCT_BOUNCE_BINDING_ANISO 4
#define DYNGI_VCT_BOUNCE_BINDING_OUT 5
// vct_mips: one level of the radiance mip chain (isotropic) or of the six-direction atlas
#define DYNGI_VCT_MIPS_BINDING_SOURCE 0
#define DYNGI_VCT_MIPS_BINDING_DEST 1
#define DYNGI_VCT_MIPS_BINDING_SEEN 2
// The anisotropic atlas is built over the SVO's occupied nodes only (the rest of it is cleared):
#define DYNGI_VCT_MIPS_BINDING_NODE_CELLS 3
#define DYNGI_VCT_MIPS_BINDING_LEVELS 4
// vct_trace: the screen's cones; vct_upsample: to full resolution
#define DYNGI_VCT_TRACE_BINDING_FRAME 0
#define DYNGI_VCT_TRACE_BINDING_G_POSITION 1
#define DYNGI_VCT_TRACE_BINDING_G_NORMAL 2
#define DYNGI_VCT_TRACE_BINDING_RADIANCE 3
#define DYNGI_VCT_TRACE_BINDING_ANISO 4
#define DYNGI_VCT_TRACE_BINDING_OUT_DIFFUSE 5
#define DYNGI_VCT_TRACE_BINDING_OUT_SPECULAR 6
// vct_reproject: the traced pixels not traced this frame, from last frame's (trace amortized over frames)
#define DYNGI_VCT_REPROJECT_BINDING_FRAME 0
#define DYNGI_VCT_REPROJECT_BINDING_G_POSITION 1
#define DYNGI_VCT_REPROJECT_BINDING_G_NORMAL 2
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_DIFFUSE 3
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SPECULAR 4
#define DYNGI_VCT_REPROJECT_BINDING_PREVIOUS_SURFACE 5
#define DYNGI_VCT_REPROJECT_BINDING_OUT_DIFFUSE 6
#define DYNGI_VCT_REPROJECT_BINDING_OUT_SPECULAR 7
#define DYNGI_VCT_REPROJECT_BINDING_OUT_SURFACE 8
#define DYNGI_VCT_UPSAMPLE_BINDING_G_POSITION 0
#define DYNGI_VCT_UPSAMPLE_BINDING_G_NORMAL 1
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_DIFFUSE 2
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_SPECULAR 3
#define DYNGI_VCT_UPSAMPLE_BINDING_OUT_DIFFUSE 4
#define DYNGI_VCT_UPSAMPLE_BINDING_OUT_SPECULAR 5
#define DYNGI_VCT_UPSAMPLE_BINDING_FRAME 6
#define DYNGI_VCT_UPSAMPLE_BINDING_LOW_SURFACE 7
#define DYNGI_VCT_FILTER_BINDING_FRAME 0
#define DYNGI_VCT_FILTER_BINDING_SURFACE 1
#define DYNGI_VCT_FILTER_BINDING_IN 2
#define DYNGI_VCT_FILTER_BINDING_OUT 3
// vct_debug: views over the HDR image
#define DYNGI_VCT_DEBUG_BINDING_FRAME 0
#define DYNGI_VCT_DEBUG_BINDING_RADIANCE 1
#define DYNGI_VCT_DEBUG_BINDING_ANISO 2
#define DYNGI_VCT_DEBUG_BINDING_INDIRECT 3
#define DYNGI_VCT_DEBUG_BINDING_SPECULAR 4
#define DYNGI_VCT_DEBUG_BINDING_OUT_HDR 5
// vct_cone_probe (tests): cones along given rays
#define DYNGI_VCT_PROBE_BINDING_RAYS 0
#define DYNGI_VCT_PROBE_BINDING_RADIANCE 1
#define DYNGI_VCT_PROBE_BINDING_ANISO 2
#define DYNGI_VCT_PROBE_BINDING_RESULTS 3
// The six directions of the anisotropic atlas, in slab order: a cone travelling along +x reads slab 0.
#define DYNGI_VCT_SLABS 6u
// The cone march (vct_cone.glsl and its C++ twin, vct_cpu.cpp): most steps a cone takes, and its
// footprint's largest fraction of its distance from the surface it left.
#define DYNGI_VCT_MAX_STEPS 160
#define DYNGI_VCT_SURFACE_CLEARANCE 0.5
// Footprints under 2^this voxels (11) read the nearest whole mip level (vctReadLevel): levels up to 8 voxels.
#define DYNGI_VCT_WHOLE_LEVELS_BELOW 3.5
// The atlas' first level (vct_mips.comp and vctAnisoDownsample): a one-sided voxel whose normal's
// component along an axis is under this in size is parallel to that axis, seen from both of its sides
// (so that the normal's rounding does not hide a floor from one side).
#define DYNGI_VCT_PARALLEL 0.1
// Which cones see an occupied voxel's radiance, in the alpha of the direct-radiance volume (vct_inject.comp
// writes it, the atlas' first level reads it: vct_seen.glsl, vctSeenMask in vct_cpu.cpp): 1 + a 6-bit
// mask, 0 for an empty voxel. Bit 2 axis is set when a cone travelling along +axis meets the voxel's
// front, bit 2 axis + 1 along -axis; a voxel whose fragments face both ways has all six
// (DYNGI_VCT_SEEN_BOTH_SIDES).
#define DYNGI_VCT_SEEN_BOTH_SIDES 63u

// Bindings of the shared indirect gather (gather.glsl); a technique's gather variant adds its own after
// them (temporal_gather.comp).
#define DYNGI_GATHER_BINDING_FRAME 0
#define DYNGI_GATHER_BINDING_POSITION 1
#define DYNGI_GATHER_BINDING_NORMAL 2
#define DYNGI_GATHER_BINDING_VPLS 3
#define DYNGI_GATHER_BINDING_SVO_NODES 4
#define DYNGI_GATHER_BINDING_OUTPUT 5
#define DYNGI_GATHER_BINDING_VISIBILITY_BITS 6
#define DYNGI_GATHER_BINDING_CLAMP_SPREAD 7  // the clamp spread's table (shared/clamp_spread.h)
#define DYNGI_GATHER_FIRST_TECHNIQUE_BINDING 8
#define DYNGI_TEMPORAL_GATHER_BINDING_SET_SAMPLES (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 0)
#define DYNGI_TEMPORAL_GATHER_BINDING_SUMS (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 1)
#define DYNGI_TEMPORAL_GATHER_BINDING_QUEUE (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 2)
#define DYNGI_TEMPORAL_GATHER_BINDING_QUEUE_ARGS (DYNGI_GATHER_FIRST_TECHNIQUE_BINDING + 3)

// GatherPush::visibility: how the gather decides whether a VPL sees a pixel.
#define DYNGI_VISIBILITY_SVO 0u   // march the SVO (nodes buffer)
#define DYNGI_VISIBILITY_NONE 1u  // V = 1
#define DYNGI_VISIBILITY_BITS 2u  // precomputed bits (Embree on the CPU)

// Settings of the indirect gather (push constants).
#ifdef __cplusplus
struct alignas(16) GatherPush {
#else
struct GatherPush {
#endif
  vec4 worldToVoxel;    // xyz origin, w 1 / voxel size
  float distanceClamp;  // B (world units^2): G = cos cos / max(B, d^2)
  float luminanceThreshold;  // relative to the first VPL's luminance
  float liftVoxels;     // SVO visibility: segment ends leave their surface by this many voxels
  float voxelResolution;
  uint vplCount;        // VPLs gathered (this set's)
  uint interleave;      // K
  uint visibility;      // DYNGI_VISIBILITY_*
  uint svoDepth;
  uint firstVpl;        // offset into the VPL buffer
  uint bitsPerPixel;    // DYNGI_VISIBILITY_BITS: visibility bits per pixel
  // The VPLs whose summed light the gathered ones estimate: vplCount, or a temporal set's size when
  // a GI budget gathers an evenly spread subset of it (each sub-image's sum is scaled by this over the
  // VPLs it gathered, so every sub-image is an unbiased estimate of the whole).
  uint estimatedCount;
  uint firstBit;        // DYNGI_VISIBILITY_BITS: where this gather's block of bits starts (one block a set)
  // The VPLs [chunkBegin, chunkEnd) of this dispatch (IndirectGatherPass::record splits a gather that
  // would give a pixel more than DYNGI_GATHER_MAX_VPLS_PER_PIXEL); chunkBegin is a multiple of K^2, and a
  // dispatch after the first adds the light the earlier ones left in the output.
  uint chunkBegin;
  uint chunkEnd;
  float clampSpread;    // the light the clamp drops is spread back, stretched this much along corners (shared/clamp_spread.h); 0: off
  uint chunkPad1;
};

// VPLs one gather dispatch gives a pixel at most. lavapipe counts every loop iteration of a shader
// invocation against one shared limit (65535, gallivm's loop limiter) and past it runs every loop once:
// a pixel gathering ~1000 VPLs (each an SVO march of a few hundred descent and step iterations) stopped
// part way, and whole workgroups came out dark. 64 leaves each VPL 1024 iterations.
#define DYNGI_GATHER_MAX_VPLS_PER_PIXEL 64u

#define DYNGI_MAX_RSM_LAYERS 24

// Temporal sets at most (set counts in bit masks; the set cameras are a uniform array of this size).
#define DYNGI_MAX_TEMPORAL_SETS 32

// The camera a temporal set's indirect buffer was gathered from (uniform array, one per set): enough to
// project a point into it and to rebuild the point a stored pixel's view depth stands for (the pixel rays
// of engine FrameUniforms).
#ifdef __cplusplus
struct alignas(16) TemporalSetCamera {
#else
struct TemporalSetCamera {
#endif
  mat4 viewProj;
  vec4 position;        // xyz camera position
  vec4 pixelRay0;       // xyz ray through pixel (0, 0)'s centre at unit view depth
  vec4 pixelRayStepX;   // xyz per pixel to the right
  vec4 pixelRayStepY;   // xyz per pixel down
};

// Temporal accumulation settings (push constants).
#ifdef __cplusplus
struct alignas(16) AccumulatePush {
#else
struct AccumulatePush {
#endif
  uint setCount;        // T
  uint currentSet;      // the set gathered this frame
  uint storedSets;      // bits: sets stored at least once
  uint setsFromThisCamera;  // bits: sets stored from the current camera
  // 1: incremental (camera as last frame, currentSet last stored from it, sums current; the gather
  // queues the pixels the reprojection takes); 0: the reprojection takes every pixel.
  uint incremental;
  uint currentSetWasStored;  // 1: currentSet held a sample before this frame
  uint pad0, pad1;
  float reprojectionCutoff;  // relative to the view distance
  float pad2, pad3, pad4;
};

// The pixels the gather queues for the full reprojection (storage buffer, reset every frame); its first
// three words are the reprojection pass's indirect dispatch (VkDispatchIndirectCommand).
#ifdef __cplusplus
struct alignas(16) TemporalQueue {
#else
struct TemporalQueue {
#endif
  uvec4 dispatchAndCount;  // x workgroups of 64 (raised by the thread that queues every 64th pixel), y 1, z 1,
                           // w pixels queued
};


// Push constants of the GI module's compute passes. Each block's members are written once, here: C++
// gets a struct of that layout (sizes checked below), each shader a push_constant block whose members it
// reads as plain names, e.g. `layout(push_constant) uniform Push { DYNGI_SVO_MARK_PUSH };`. Members are
// scalars after an optional leading vec4, so std430 and C++ place them alike.
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
#define DYNGI_VPL_CDF_ROWS_PUSH uint res; uint layers;
#define DYNGI_VPL_CDF_TOTAL_PUSH uint rows;
#define DYNGI_VPL_SAMPLE_PUSH uint res; uint layers; uint count; uint seed;
#define DYNGI_VPL_BOUNCE_PUSH                                                        \
  vec4 worldToVoxel; /* xyz origin, w 1 / voxel size */                            \
  uint parentFirst;  /* first VPL of bounce b-1 */                                 \
  uint count;        /* VPLs per bounce */                                         \
  uint bounce;                                                                     \
  uint depth;                                                                      \
  float res;                                                                       \
  float lift;        /* voxel units the ray starts off its surface */ \
  uint seed;         /* VplOptions::seed: turns every bounce's Halton points (Cranley-Patterson) */
#define DYNGI_VPL_TAIL_PUSH                                                          \
  uint lastFirst;    /* first VPL of the last gathered bounce; its probes follow it */ \
  uint count;        /* VPLs per bounce */
#define DYNGI_MANY_LIGHTS_DEBUG_PUSH uint mode; uint K; uint vplCount;
#define DYNGI_INDIRECT_FILTER_PUSH float planeTolerance;
#define DYNGI_COMPENSATE_PUSH                                                        \
  float distanceClamp;   /* B: the gather's G = cos cos / max(B, d^2) */            \
  uint rays;             /* per traced texel */                                     \
  uint includeIndirect;  /* 1: the VPLs carry light that bounced before (bounces > 1 or the tail) */ \
  uint lightCount;                                                              \
  float planeTolerance;  /* blur: taps within this fraction of the view distance off the texel's plane */
// The cone parameters every VCT pass that marches cones shares (vct_cone.glsl reads them by name).
#define DYNGI_VCT_CONE_PARAMS                                                        \
  vec4 volume;       /* xyz world origin, w voxel size */                          \
  float res;         /* voxels per side */                                         \
  float maxDistance; /* voxels a diffuse cone marches */                           \
  float aoDistance;  /* voxels over which occlusion counts towards AO */          \
  float coneOffset;  /* voxels off the surface a cone starts */                   \
  float stepScale;   /* step = this x the cone's diameter */                       \
  uint cones;        /* diffuse cones */                                           \
  float farNarrowing; /* footprints over 2^DYNGI_VCT_WHOLE_LEVELS_BELOW read 2^-this of theirs */
#define DYNGI_VCT_INJECT_PUSH                                                        \
  vec4 volume;       /* xyz world origin, w voxel size */                          \
  uint lightCount;                                                                 \
  uint history;      /* 1: DIRECT holds last frame's radiance */                  \
  float temporalBlend;                                                             \
  float temporalResponse;
#define DYNGI_VCT_CLEAR_PUSH uint runCount; uint depth; /* the SVO's: its leaves are level-0 voxels, level depth - 1 the atlas' level-0 texels */ \
  uint atlasSlabWidth; /* texels; 0: isotropic, no atlas */
#define DYNGI_VCT_BOUNCE_PUSH DYNGI_VCT_CONE_PARAMS uint commit; /* 0 trace, 1 copy OUT to RADIANCE */
#define DYNGI_VCT_MIPS_PUSH uint destSlabWidth; /* texels; the isotropic chain has one slab */ uint sourceSlabWidth; /* 0: one source slab */ \
  uint nodeLevel; /* anisotropic: the SVO level whose cells are this atlas level's texels */
#define DYNGI_VCT_TRACE_PUSH DYNGI_VCT_CONE_PARAMS uint traceScale; uint specular; uint turnCones; /* 1: each traced pixel turns its cone set */ \
  float specularConeBelow; /* VctOptions::specularConeBelow: rougher pixels march no specular cone */ \
  uint traceFrames; /* 1, 2 or 4: the frames over which every traced pixel is traced once */ uint tracePhase; /* frame index mod traceFrames */ \
  uint coneInterleave; /* rows of traced pixels take turns over the cone set: each traces every this-many-th cone */
#define DYNGI_VCT_REPROJECT_PUSH                                                     \
  mat4 previousViewProj;                                                           \
  uint traceScale;                                                                 \
  uint traceFrames;                                                                \
  uint tracePhase;                                                                 \
  uint history;      /* 0: nothing from last frame counts (first frame, light switched) */ \
  uint maxAge;       /* frames a reprojected value may go untraced before it is dropped */
#define DYNGI_VCT_UPSAMPLE_PUSH uint traceScale; float specularConeBelow; /* VctOptions::specularConeBelow */
// The roughness range under VctOptions::specularConeBelow over which the specular light blends from the
// cone's into the diffuse light's (vct_upsample.comp).
#define DYNGI_VCT_SPECULAR_BLEND 0.2
#define DYNGI_VCT_FILTER_PUSH uint traceScale; int radius; /* traced pixels */ int axisX; int axisY; /* (1, 0) or (0, 1) */
#define DYNGI_VCT_DEBUG_PUSH DYNGI_VCT_CONE_PARAMS uint mode; float mip;
#define DYNGI_VCT_PROBE_PUSH DYNGI_VCT_CONE_PARAMS uint count; float tanHalf;

#ifdef __cplusplus
using uint = uint32_t;
struct SvoMarkPush { DYNGI_SVO_MARK_PUSH };
struct SvoLevelPush { DYNGI_SVO_LEVEL_PUSH };
struct SvoExpandPush { DYNGI_SVO_EXPAND_PUSH };
struct SvoLeafAttributesPush { DYNGI_SVO_LEAF_ATTRIBUTES_PUSH };
struct SvoVoxelAttributesPush { DYNGI_SVO_VOXEL_ATTRIBUTES_PUSH };
struct SvoMarchPush { DYNGI_SVO_MARCH_PUSH };
struct VoxelDebugPush { DYNGI_VOXEL_DEBUG_PUSH };
struct VplCdfRowsPush { DYNGI_VPL_CDF_ROWS_PUSH };
struct VplCdfTotalPush { DYNGI_VPL_CDF_TOTAL_PUSH };
struct VplSamplePush { DYNGI_VPL_SAMPLE_PUSH };
struct VplBouncePush { DYNGI_VPL_BOUNCE_PUSH };
struct VplTailPush { DYNGI_VPL_TAIL_PUSH };
struct ManyLightsDebugPush { DYNGI_MANY_LIGHTS_DEBUG_PUSH };
struct IndirectFilterPush { DYNGI_INDIRECT_FILTER_PUSH };
struct CompensatePush { DYNGI_COMPENSATE_PUSH };
struct VctInjectPush { DYNGI_VCT_INJECT_PUSH };
struct VctClearPush { DYNGI_VCT_CLEAR_PUSH };
struct VctBouncePush { DYNGI_VCT_BOUNCE_PUSH };
struct VctMipsPush { DYNGI_VCT_MIPS_PUSH };
struct VctTracePush { DYNGI_VCT_TRACE_PUSH };
struct VctReprojectPush { DYNGI_VCT_REPROJECT_PUSH };
struct VctUpsamplePush { DYNGI_VCT_UPSAMPLE_PUSH };
struct VctFilterPush { DYNGI_VCT_FILTER_PUSH };
struct VctDebugPush { DYNGI_VCT_DEBUG_PUSH };
struct VctProbePush { DYNGI_VCT_PROBE_PUSH };
#endif

#ifdef __cplusplus
static_assert(sizeof(VoxelizePush) == 128);
static_assert(sizeof(GpuVpl) == 48);
static_assert(sizeof(RsmPush) == 128);
static_assert(sizeof(RsmLayer) == 96);
static_assert(sizeof(GatherPush) == 80);
static_assert(sizeof(TemporalSetCamera) == 128);
static_assert(sizeof(AccumulatePush) == 48);
// The temporal gather's push constants (GatherPush, then AccumulatePush): Vulkan guarantees 128 bytes.
static_assert(sizeof(GatherPush) + sizeof(AccumulatePush) <= 128);
static_assert(sizeof(TemporalQueue) == 16);
static_assert(sizeof(SvoLevel) == 32);
static_assert(sizeof(SvoCounters) == 16);
static_assert(sizeof(SvoMarkPush) == 8 && sizeof(SvoLevelPush) == 8 && sizeof(SvoExpandPush) == 12);
static_assert(sizeof(SvoLeafAttributesPush) == 16 && sizeof(SvoVoxelAttributesPush) == 8 && sizeof(SvoMarchPush) == 32 && sizeof(VoxelDebugPush) == 28);
static_assert(sizeof(VplCdfRowsPush) == 8 && sizeof(VplCdfTotalPush) == 4 && sizeof(VplSamplePush) == 16);
static_assert(sizeof(VplTailPush) == 8 && sizeof(CompensatePush) == 20);
static_assert(sizeof(VplBouncePush) == 44 && sizeof(ManyLightsDebugPush) == 12 && sizeof(IndirectFilterPush) == 4);
static_assert(sizeof(VctInjectPush) == 32 && sizeof(VctClearPush) == 12 && sizeof(VctBouncePush) == 48 && sizeof(VctMipsPush) == 12);
static_assert(sizeof(VctTracePush) == 72 && sizeof(VctReprojectPush) == 84 && sizeof(VctUpsamplePush) == 8 && sizeof(VctFilterPush) == 16 && sizeof(VctDebugPush) == 52 && sizeof(VctProbePush) == 52);
}  // namespace dyngi::gi::gpu
#endif

#endif
