#pragma once
// dyngi's GI inside a host's own renderer: the host's Vulkan device, its command buffer, its G-buffer
// and its scene, fed through calls. No dyngi renderer, world or importer on the host's side.
//
//   1. Device: merge GiContext::requirements() into the host's VkInstanceCreateInfo / VkDeviceCreateInfo,
//      then make a GiContext from the host's handles (it owns none of them).
//   2. Scene: add meshes, textures, materials, instances and lights; update and remove them as the game
//      changes them. What changed since the last frame is what the calls said.
//   3. Frame: recordFrame(cmd, desc) records the GI into the host's command buffer: the camera, the
//      host's G-buffer (views and how they are encoded) and where the indirect light goes.
//
// The frame contract (docs/INTEGRATION.md, "The frame"):
// - Inputs are read in the layouts GBufferDesc states (colorLayout, depthLayout),
//   after a barrier the GI records from every earlier stage; they stay in those layouts.
// - Outputs the host owns are written in GENERAL (their formats: RGBA16F or RGBA32F, storage usage) and
//   left in GENERAL after a barrier that makes the writes visible to later compute and fragment reads.
// - recordFrame never waits on the device. The host submits the command buffer, and waits for it (its
//   fence) before the next recordFrame: the GI keeps one frame in flight. Scene calls may upload
//   through one-off submissions on the host's queue and wait for them: call them on the thread that
//   owns the queue, outside the host's own submissions.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/device_requirements.h"
#include "dyngi/gi/gi_settings.h"

namespace dyngi::gi {

class GiSystem;

using MeshHandle = uint32_t;
using TextureHandle = uint32_t;
using MaterialHandle = uint32_t;
using InstanceHandle = uint32_t;
using LightHandle = uint32_t;
constexpr uint32_t kNoHandle = UINT32_MAX;

// Triangles from host memory (copied): positions, and per vertex normals and uvs when given (else flat
// normals and uv 0), 32-bit indices, three a triangle.
struct MeshDesc {
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;
  std::span<const glm::vec2> uvs;
  std::span<const uint32_t> indices;
  std::string name;
};

// RGBA8 pixels, row-major, top row first (copied).
struct TextureDesc {
  uint32_t width = 0, height = 0;
  std::span<const uint8_t> rgba8;
  bool srgb = true;  // colour textures: sRGB; data (metallic-roughness): linear
};

// glTF's metallic-roughness material: factors, and textures (kNoHandle: none) they multiply. Factors are
// clamped into glTF's ranges, emission into [0, scene::kMaxEmission] (docs/CONTENT.md).
struct MaterialDesc {
  glm::vec4 baseColor{1.0f};
  glm::vec3 emissive{0.0f};  // outgoing radiance (glTF's emissiveFactor x emissive strength)
  float metallic = 0.0f;
  float roughness = 1.0f;
  TextureHandle baseColorTexture = kNoHandle;
  TextureHandle emissiveTexture = kNoHandle;
  TextureHandle metallicRoughnessTexture = kNoHandle;  // glTF's: roughness in green, metallic in blue
};

struct InstanceDesc {
  MeshHandle mesh = kNoHandle;
  MaterialHandle material = kNoHandle;  // kNoHandle: white, rough
  glm::mat4 transform{1.0f};            // object to world
  bool dynamic = true;                  // false: a hint that it will not move (its voxels and shadows kept)
};

// glTF's punctual lights, in its units (README, "Light units"); lights point down their -Z. Values are
// clamped into the importer's ranges (intensity <= scene::kMaxLightIntensity; docs/CONTENT.md).
struct LightDesc {
  enum class Type { Directional, Point, Spot };
  Type type = Type::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // where it shines (directional, spot)
  float range = 0.0f;                      // 0: unlimited
  float innerConeAngle = 0.0f, outerConeAngle = 0.7853982f;
  bool enabled = true;
};

// How the host's G-buffer is encoded. Every view is sampled at the render size, pixel for pixel.
struct GBufferDesc {
  VkImageView depth = VK_NULL_HANDLE;  // D32 / D24 / D16, or a colour format holding depth in r
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  bool reversedZ = false;              // far at depth 0
  VkImageView normal = VK_NULL_HANDLE;
  enum class NormalEncoding { WorldXyz, ViewXyz, WorldOctahedral, ViewOctahedral };
  NormalEncoding normalEncoding = NormalEncoding::WorldXyz;
  float normalScale = 1.0f, normalBias = 0.0f;  // xyz (or the octahedral xy) = stored * scale + bias
  VkImageView baseColor = VK_NULL_HANDLE;  // rgb linear base colour (an sRGB view decodes it)
  VkImageView roughness = VK_NULL_HANDLE;  // any view, the normal's or the base colour's too (null: 1)
  uint32_t roughnessChannel = 3;           // 0 r, 1 g, 2 b, 3 a
  bool perceptualRoughness = true;         // stored as glTF's roughness (false: alpha = roughness^2)
  VkImageView metallic = VK_NULL_HANDLE;   // null: 0
  uint32_t metallicChannel = 3;
  VkImageView emissive = VK_NULL_HANDLE;   // optional: rgb emitted radiance
  VkImageLayout colorLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;  // every view but the depth
};

struct CameraDesc {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};  // Vulkan clip space (y down, depth 0..1, or 1..0 with reversedZ)
};

// Where the GI writes this frame. A null view: the GI's own image (GiContext::indirectView, specularView).
struct OutputDesc {
  VkImageView indirect = VK_NULL_HANDLE;  // E / pi (what the host multiplies by the diffuse albedo)
  VkFormat indirectFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // RGBA16F or RGBA32F, with storage usage
  VkImageView specular = VK_NULL_HANDLE;  // indirect specular radiance along the reflected view ray
  VkFormat specularFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
};

struct FrameDesc {
  uint32_t width = 0, height = 0;
  CameraDesc camera;
  GBufferDesc gbuffer;
  OutputDesc outputs;
  double time = 0.0;  // seconds: the GI's clock (animated emitters, budget windows)
};

class GiContext {
 public:
  // What the host's instance and device must have for these settings (the techniques that use a voxel
  // scene need geometry shaders and fragment stores).
  static render::DeviceRequirements requirements();
  // Throws std::runtime_error naming what the device lacks (one line), or an unknown technique.
  GiContext(const render::ExternalDevice& device, const GiSettings& settings = {});
  ~GiContext();
  GiContext(const GiContext&) = delete;
  GiContext& operator=(const GiContext&) = delete;

  MeshHandle addMesh(const MeshDesc& mesh);
  // New vertex positions and normals for a mesh (CPU skinning): from then on its instances deform, as
  // the ECS path's skinned meshes do: each update re-voxelizes them, refits them and invalidates their VPLs.
  void updateMesh(MeshHandle mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  TextureHandle addTexture(const TextureDesc& texture);
  MaterialHandle addMaterial(const MaterialDesc& material);
  void updateMaterial(MaterialHandle material, const MaterialDesc& desc);  // every instance using it
  InstanceHandle addInstance(const InstanceDesc& instance);
  void setTransform(InstanceHandle instance, const glm::mat4& transform);
  void setMaterial(InstanceHandle instance, MaterialHandle material);
  void removeInstance(InstanceHandle instance);
  LightHandle addLight(const LightDesc& light);
  void updateLight(LightHandle light, const LightDesc& desc);
  void removeLight(LightHandle light);

  // Records the GI for one frame into `cmd` (recording, on the host's queue family). Throws
  // std::invalid_argument for a FrameDesc it cannot read (a missing view, a zero size).
  void recordFrame(VkCommandBuffer cmd, const FrameDesc& frame);
  // The GI's own output images (GENERAL layout, RGBA32F and RGBA16F), valid after the first frame.
  VkImageView indirectView() const;
  VkImageView specularView() const;

  // The GI as the ECS path has it: technique, options as used, debug views, stats, budget, reset().
  GiSystem& system();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dyngi::gi
