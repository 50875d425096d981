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

#endif
