#pragma once
// What a pass (built-in or a plugged-in render feature) sees while recording one frame.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "dyngi/engine/render/gpu_timer.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/engine/render/resources.h"
#include "dyngi/engine/render/snapshot.h"
#include "shared/gpu_types.h"

namespace dyngi::render {

// Screen-sized images of one frame. All are left in VK_IMAGE_LAYOUT_GENERAL after the pass that writes
// them, so later passes can sample or load them without knowing who wrote them.
struct RenderTargets {
  uint32_t width = 0, height = 0;
  Image position;   // RGBA32F: xyz world position, w = 1 where geometry was hit
  Image normal;     // RGBA16F: xyz world normal (facing the camera), w roughness
  Image albedo;     // RGBA8:   rgb linear base colour, a metallic
  Image emissive;   // RGBA16F: rgb emitted radiance
  Image depth;      // D32
  Image indirect;   // RGBA32F: written by GI features (E_indirect / pi); cleared to 0 otherwise
  Image specular;   // RGBA16F: indirect specular radiance along the reflected view ray, written by a GI
                    // feature that sets FrameContext::specular to SpecularSource::Target; lighting
                    // weighs it by the specular colour (split-sum fit of the GGX BRDF)
  Image hdr;        // RGBA32F: emission + direct + albedo * indirect, linear radiance before exposure
  Image ldr;        // RGBA8:   tone-mapped, sRGB-encoded display image
};

// Geometry of one mesh on the GPU. Vertex layout: GpuVertex (position, normal, uv), 32 bytes.
struct GpuVertex {
  float position[3];
  float normal[3];
  float uv[2];
};
static_assert(sizeof(GpuVertex) == 32);

// A GpuVertex buffer at binding 0 as a pipeline's vertex input: position at location 0, then normal at
// location 1 and uv at location 2 for the shaders that read them.
inline void setMeshVertexInput(Pipeline::GraphicsDesc& d, bool normal, bool uv) {
  d.vertexBindings = {{0, sizeof(GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  d.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position)}};
  if (normal) d.vertexAttributes.push_back({1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal)});
  if (uv) d.vertexAttributes.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv)});
}
// Adds the tangents (GpuMesh::tangents, binding 1) at location 3.
inline void setMeshTangentInput(Pipeline::GraphicsDesc& d) {
  d.vertexBindings.push_back({1, sizeof(float) * 4, VK_VERTEX_INPUT_RATE_VERTEX});
  d.vertexAttributes.push_back({3, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 0});
}

struct GpuMesh {
  Buffer vertices;
  Buffer tangents;  // vec4 per vertex at binding 1 (location 3), for meshes with tangents (normal textures)
  Buffer indices;
  uint32_t indexCount = 0;
  uint32_t version = 0;
};

// Viewport (depth 0..1) and scissor covering a width x height target: every pass draws to its whole target.
inline void setFullViewport(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  VkViewport vp{0, 0, float(width), float(height), 0, 1};
  VkRect2D sc{{0, 0}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

// Binds a mesh's vertex buffers (the tangents too when it has them) and its index buffer.
inline void bindMesh(VkCommandBuffer cmd, const GpuMesh& mesh) {
  VkDeviceSize offset = 0;
  VkBuffer vertices = mesh.vertices.handle();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
  if (mesh.tangents.valid()) {  // read by the pipelines that declare binding 1 (setMeshTangentInput)
    VkBuffer tangents = mesh.tangents.handle();
    vkCmdBindVertexBuffers(cmd, 1, 1, &tangents, &offset);
  }
  vkCmdBindIndexBuffer(cmd, mesh.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
}

// The frame's lights as the lighting pass sees them, for a feature that lights something itself
// (radiance injection into a voxel volume): the GpuLight list, one view-projection per shadow layer and
// the r32f lookup layers, which engine/shaders/shared/shadows.glsl reads. Valid while recording features.
struct LightInputs {
  const Buffer* lights = nullptr;          // GpuLight[count]
  const Buffer* shadowMatrices = nullptr;  // mat4 per shadow layer
  Image* shadowMaps = nullptr;             // r32f 2D array, GENERAL layout
  uint32_t count = 0;
};

// Where the lighting pass takes the indirect specular radiance it weighs by the specular colour.
enum class SpecularSource : uint8_t {
  None,      // no feature gave any: no indirect specular term
  Target,    // targets.specular, written by a GI feature
  Indirect,  // the feature's specular light is its diffuse light at every pixel (targets.indirect's E / pi:
             // a split-sum prefiltered radiance at roughness 1), e.g. a scene without glossy surfaces;
             // targets.specular is not written, and the lighting reads one image instead of two
};

// The frame's draws as gpu::DrawRecord records in one storage buffer (their materials' records after
// them), in an order where draws that share a mesh and a material's textures (so a pipeline and
// descriptors in every raster pass) are consecutive: a pass draws each run of them with one instanced draw (drawBatched), each instance
// reading its record at gl_InstanceIndex. Built by the renderer once a frame; valid while recording.
struct FrameInstances {
  const Buffer* records = nullptr;     // gpu::DrawRecord per slot, then gpu::DrawMaterialRecord per snapshot material
  std::vector<uint32_t> slotOfDraw;    // indexed like snapshot.draws
  std::vector<uint32_t> drawOfSlot;
  std::vector<uint32_t> batchOfSlot;   // equal for neighbouring slots that one instanced draw may hold
};

struct FrameContext {
  VulkanContext& ctx;
  VkCommandBuffer cmd;
  GpuTimer* timer;
  const RenderSnapshot& snapshot;
  RenderTargets& targets;
  const Buffer& frameUniforms;            // gpu::FrameUniforms, as the shaders see them
  const gpu::FrameUniforms& uniforms;     // the same values on the CPU (camera matrices, pixel rays)
  const std::vector<GpuMesh*>& meshes;    // indexed like snapshot.draws
  VkSampler linearSampler;
  VkSampler nearestSampler;
  // The view of a scene texture (a 1x1 white texture for kNoTexture or a missing one).
  std::function<VkImageView(scene::TextureId)> textureView;
  // Submits what was recorded so far, waits for it, and reopens `cmd` for the rest of the frame. For a
  // feature that needs this frame's G-buffer on the CPU (ray-traced visibility); costs the overlap.
  std::function<void()> submitAndWait;
  LightInputs lights;
  const FrameInstances* instances = nullptr;
  // Where a feature put this frame's indirect specular radiance (SpecularSource).
  SpecularSource specular = SpecularSource::None;
};

}  // namespace dyngi::render
