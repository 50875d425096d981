// Struct layouts shared by C++ and GLSL: the one place they are defined.
// C++ sees glm types inside namespace dyngi::gpu; GLSL sees its own vec4/mat4.
// Every struct is made of 16-byte members so std140 and std430 agree with C++.
#ifndef DYNGI_GPU_TYPES_H
#define DYNGI_GPU_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace dyngi::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#define DYNGI_GPU_STRUCT(name) struct alignas(16) name
#else
#define DYNGI_GPU_STRUCT(name) struct name
#endif

#define DYNGI_LIGHT_DIRECTIONAL 0
#define DYNGI_LIGHT_POINT 1
#define DYNGI_LIGHT_SPOT 2
#define DYNGI_MAX_LIGHTS 64
#define DYNGI_NO_SHADOW 0xFFFFFFFFu

// Per-frame camera and settings (uniform buffer, binding 0 of most passes).
DYNGI_GPU_STRUCT(FrameUniforms) {
  mat4 view;
  mat4 proj;
  mat4 viewProj;
  mat4 invViewProj;
  vec4 cameraPos;       // xyz world position
  uvec4 sizeAndCount;   // x width, y height, z light count, w frame index
  vec4 exposure;        // x linear exposure multiplier, y tone-map operator (0 ACES fit, 1 none/clamp)
  vec4 background;      // rgb radiance where no geometry is hit
  // Pixel rays at unit view depth: the surface seen through the centre of pixel q at view depth t
  // (distance along viewForward) is cameraPos + t * (pixelRay0 + q.x * pixelRayStepX + q.y * pixelRayStepY).
  // Lets a pass store one float per pixel instead of a world position.
  vec4 viewForward;     // xyz unit view direction (world)
  vec4 pixelRay0;       // xyz ray through pixel (0, 0)'s centre, scaled to unit view depth
  vec4 pixelRayStepX;   // xyz change per pixel to the right
  vec4 pixelRayStepY;   // xyz change per pixel down
};

// One light (storage buffer). Directions are unit vectors the light points along.
DYNGI_GPU_STRUCT(GpuLight) {
  vec4 positionType;    // xyz world position, w type (DYNGI_LIGHT_*)
  vec4 directionRange;  // xyz direction, w range (0: infinite)
  vec4 radiance;        // rgb color * intensity, w enabled (0/1)
  vec4 cone;            // x cos(outer), y cos(inner), z first shadow layer (as float; <0: none), w normal-offset scale
};

// The frame's draw records as the raster passes read them (one storage buffer, FrameInstances): a record
// per draw slot, then one per material of the snapshot, each 64 bytes. Draws sharing a mesh and textures
// go in one instanced draw, each instance reading its record at gl_InstanceIndex (draw_instances.glsl
// assembles the draw's transform and material from its two records).
DYNGI_GPU_STRUCT(DrawRecord) {
  vec4 modelRows[3];    // the model matrix's first three rows (the fourth is 0 0 0 1)
  uvec4 material;       // x: the index of its material's record
};
DYNGI_GPU_STRUCT(DrawMaterialRecord) {
  vec4 baseColor;       // rgb linear factor; a: alphaMaskThreshold() for masked materials, else 1 (alpha is not stored)
  vec4 emissive;        // rgb outgoing radiance factor, w's bits: packHalf2x16(occlusion strength, normal scale)
  vec4 params;          // x metallic, y roughness, zw the texture coordinates' offset (KHR_texture_transform)
  vec4 uvLinear;        // the texture coordinates' linear map (shared/uv_transform.h)
};

// Descriptor bindings of the engine's passes (set 0, push descriptors): the shaders declare them and the
// C++ binds them by these names.
// gbuffer
#define DYNGI_GBUFFER_BINDING_FRAME 0
#define DYNGI_GBUFFER_BINDING_BASE_COLOR_TEX 1
#define DYNGI_GBUFFER_BINDING_EMISSIVE_TEX 2
#define DYNGI_GBUFFER_BINDING_METALLIC_ROUGHNESS_TEX 3
#define DYNGI_GBUFFER_BINDING_OCCLUSION_TEX 4
#define DYNGI_GBUFFER_BINDING_NORMAL_TEX 5
#define DYNGI_GBUFFER_BINDING_INSTANCES 6
// shadow (alpha-masked casters)
#define DYNGI_SHADOW_BINDING_BASE_COLOR_TEX 0
#define DYNGI_SHADOW_BINDING_INSTANCES 1
// The material's textures, as bits of a pipeline variant (the G-buffer's; the voxelization and the RSMs
// use the ones they read).
#define DYNGI_MATERIAL_BASE_COLOR_TEX 1u
#define DYNGI_MATERIAL_EMISSIVE_TEX 2u
#define DYNGI_MATERIAL_METALLIC_ROUGHNESS_TEX 4u
#define DYNGI_MATERIAL_OCCLUSION_TEX 8u
#define DYNGI_MATERIAL_ALPHA_MASK 16u  // not a texture: the alpha test's variant
#define DYNGI_MATERIAL_NORMAL_TEX 32u  // set only for meshes with tangents (render::drawTextureBits)
// lighting
#define DYNGI_LIGHTING_BINDING_FRAME 0
#define DYNGI_LIGHTING_BINDING_G_POSITION 1
#define DYNGI_LIGHTING_BINDING_G_NORMAL 2
#define DYNGI_LIGHTING_BINDING_G_ALBEDO 3
#define DYNGI_LIGHTING_BINDING_G_EMISSIVE 4
#define DYNGI_LIGHTING_BINDING_LIGHTS 5
#define DYNGI_LIGHTING_BINDING_SHADOW_MATRICES 6
#define DYNGI_LIGHTING_BINDING_SHADOW_MAPS 7
#define DYNGI_LIGHTING_BINDING_INDIRECT 8
#define DYNGI_LIGHTING_BINDING_OUT_HDR 9
#define DYNGI_LIGHTING_BINDING_SPECULAR 10
// tonemap
#define DYNGI_TONEMAP_BINDING_FRAME 0
#define DYNGI_TONEMAP_BINDING_HDR 1
#define DYNGI_TONEMAP_BINDING_LDR 2

// Push constants of the shadow pass (one shadow-map layer: the casters' instances are DrawInstances) and
// of the lighting pass, as member lists: C++ gets a struct, the shader
// `layout(push_constant) uniform Push { DYNGI_SHADOW_PUSH };`.
#define DYNGI_SHADOW_PUSH mat4 lightViewProj;
#define DYNGI_LIGHTING_PUSH uint hasIndirect;  /* 0: no feature wrote indirect light */

#ifdef __cplusplus
struct ShadowPush { DYNGI_SHADOW_PUSH };
struct LightingPush { DYNGI_LIGHTING_PUSH };
static_assert(sizeof(ShadowPush) == 64);
static_assert(sizeof(LightingPush) == 4);
static_assert(sizeof(FrameUniforms) == 4 * 64 + 8 * 16);
static_assert(sizeof(GpuLight) == 64);
static_assert(sizeof(DrawRecord) == 64 && sizeof(DrawMaterialRecord) == 64);
}  // namespace dyngi::gpu
#endif

#endif
