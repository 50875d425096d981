// What every GI pass's C++/GLSL layout header starts from: the C++ names of the GLSL types, the namespace
// the C++ structs live in, and the bindings of the GI system's own views. Each part of the GI keeps its
// own layouts beside its shaders: voxel/shaders/voxel_shared.h, indirect/shaders/indirect_shared.h,
// techniques/<name>/shaders/<name>_shared.h. The engine's live in engine/shaders/shared/gpu_types.h.
//
// Conventions: 16-byte members only, so std140/std430 and C++ agree, each struct with its size and its
// members' offsets asserted. Descriptor bindings (set 0, push descriptors) are DYNGI_<PASS>_BINDING_<NAME>
// constants the shaders declare and the C++ binds by. A push-constant block's members are written once,
// as a DYNGI_<NAME>_PUSH macro: C++ gets a struct of that layout, each shader a push_constant block whose
// members it reads as plain names (`layout(push_constant) uniform Push { DYNGI_SVO_MARK_PUSH };`); members
// are scalars after an optional leading vec4, so std430 and C++ place them alike.
#ifndef DYNGI_GI_GPU_TYPES_H
#define DYNGI_GI_GPU_TYPES_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace dyngi::gi::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using mat3x4 = glm::mat3x4;
using uint = uint32_t;
}  // namespace dyngi::gi::gpu
#define DYNGI_GPU_NAMESPACE_BEGIN namespace dyngi::gi::gpu {
#define DYNGI_GPU_NAMESPACE_END }
#else
#define DYNGI_GPU_NAMESPACE_BEGIN
#define DYNGI_GPU_NAMESPACE_END
#endif

// gi_indirect_view.comp (the GI system's `indirect` view).
#define DYNGI_GI_VIEW_BINDING_INDIRECT 0
#define DYNGI_GI_VIEW_BINDING_OUT_HDR 1

// gi_gbuffer_import.comp: a host's G-buffer (gi::GiContext) into the GI's targets.
#define DYNGI_GBUFFER_IMPORT_BINDING_FRAME 0
#define DYNGI_GBUFFER_IMPORT_BINDING_DEPTH 1
#define DYNGI_GBUFFER_IMPORT_BINDING_NORMAL 2
#define DYNGI_GBUFFER_IMPORT_BINDING_BASE_COLOR 3
#define DYNGI_GBUFFER_IMPORT_BINDING_ROUGHNESS 4
#define DYNGI_GBUFFER_IMPORT_BINDING_METALLIC 5
#define DYNGI_GBUFFER_IMPORT_BINDING_EMISSIVE 6
#define DYNGI_GBUFFER_IMPORT_BINDING_OUT_POSITION 7
#define DYNGI_GBUFFER_IMPORT_BINDING_OUT_NORMAL 8
#define DYNGI_GBUFFER_IMPORT_BINDING_OUT_ALBEDO 9
#define DYNGI_GBUFFER_IMPORT_BINDING_OUT_EMISSIVE 10
// GiContext's normal encodings (GBufferDesc::NormalEncoding, in its order).
#define DYNGI_NORMAL_WORLD_XYZ 0u
#define DYNGI_NORMAL_VIEW_XYZ 1u
#define DYNGI_NORMAL_WORLD_OCTAHEDRAL 2u
#define DYNGI_NORMAL_VIEW_OCTAHEDRAL 3u
#define DYNGI_GBUFFER_IMPORT_PUSH                                                    \
  uint normalEncoding; /* DYNGI_NORMAL_* */                                        \
  float normalScale;   /* stored * scale + bias */                                 \
  float normalBias;                                                                \
  uint reversedZ;      /* 1: far at depth 0 */                                     \
  uint roughnessChannel;                                                           \
  uint metallicChannel;                                                            \
  uint squaredRoughness; /* 1: stored alpha = roughness^2 */                       \
  uint width;                                                                      \
  uint height;
// gi_export_rgba16f.comp / gi_export_rgba32f.comp: the GI's outputs into a host's image.
#define DYNGI_EXPORT_BINDING_IN 0
#define DYNGI_EXPORT_BINDING_OUT 1
#define DYNGI_EXPORT_PUSH uint width; uint height; uint zero; /* 1: writes 0 */

#ifdef __cplusplus
DYNGI_GPU_NAMESPACE_BEGIN
struct GBufferImportPush { DYNGI_GBUFFER_IMPORT_PUSH };
struct ExportPush { DYNGI_EXPORT_PUSH };
static_assert(sizeof(GBufferImportPush) == 36 && offsetof(GBufferImportPush, height) == 32);
static_assert(sizeof(ExportPush) == 12);
DYNGI_GPU_NAMESPACE_END
#endif

#endif
