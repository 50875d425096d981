#pragma once
// RAII buffers and images with their own memory (dyngi allocates few, large resources), plus the
// barrier helper every pass uses. Images remember their current layout so passes can transition
// without knowing who touched them last.
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "dyngi/engine/render/context.h"

namespace dyngi::render {

enum class MemoryUsage {
  GpuOnly,    // device-local; filled by the GPU or through upload()
  Upload,     // host-visible, written every frame by the CPU (uniforms, per-frame data)
  Readback,   // host-visible + cached when possible, read by the CPU
};

// Both classes release everything they made when their constructor throws (a destructor does not run
// for a half-built object), so an allocation refused part-way leaks nothing.
class Buffer {
 public:
  Buffer() = default;
  Buffer(VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, const char* name = nullptr);
  ~Buffer() { reset(); }
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  void reset();
  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  bool valid() const { return buffer_ != VK_NULL_HANDLE; }
  void* mapped() const { return mapped_; }
  // Writes `bytes` at `offset`: directly when the buffer is host-visible, else through a staging copy.
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  void invalidateForRead();  // make GPU writes visible to mapped() on non-coherent memory
  void flush();              // make CPU writes through mapped() visible to the GPU on non-coherent memory

 private:
  void create(VkBufferUsageFlags usage, MemoryUsage memory, const char* name);
  VulkanContext* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize memoryBytes_ = 0;
  uint32_t memoryType_ = 0;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  bool coherent_ = true;
};

struct ImageDesc {
  uint32_t width = 1, height = 1, layers = 1, mips = 1;
  uint32_t depth = 1;  // > 1 only with viewType VK_IMAGE_VIEW_TYPE_3D
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT;
  VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
  const char* name = nullptr;
};

class Image {
 public:
  Image() = default;
  Image(VulkanContext& ctx, const ImageDesc& desc);
  ~Image() { reset(); }
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  void reset();
  bool valid() const { return image_ != VK_NULL_HANDLE; }
  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  // A 2D view of one array layer (shadow map faces are rendered one layer at a time).
  VkImageView layerView(uint32_t layer) const { return layerViews_.at(layer); }
  // A view of one mip level (storage images are bound a level at a time: mip chains built by compute).
  VkImageView mipView(uint32_t level) const { return mipViews_.at(level); }
  const ImageDesc& desc() const { return desc_; }
  VkExtent2D extent() const { return {desc_.width, desc_.height}; }
  VkImageAspectFlags aspect() const;
  VkImageLayout layout() const { return layout_; }

  // Records a barrier into `newLayout`. src is derived from what the image was last used for.
  void transition(VkCommandBuffer cmd, VkImageLayout newLayout, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

 private:
  void create();
  VulkanContext* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize memoryBytes_ = 0;
  uint32_t memoryType_ = 0;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> layerViews_;
  std::vector<VkImageView> mipViews_;  // one per level when mips > 1 (else the image's view)
  ImageDesc desc_;
  VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 lastStage_ = VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT;
  VkAccessFlags2 lastAccess_ = 0;
};

// Fills a sampled RGBA8 image from CPU pixels (through a staging buffer) and leaves it shader-readable.
Image createTexture(VulkanContext& ctx, uint32_t width, uint32_t height, const uint8_t* rgba8, bool srgb, const char* name);

// One image's layout transition with its dependency (an image dyngi does not own: a swapchain's, a host's).
void imageBarrier(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Full memory barrier between two stages (buffers written by one pass and read by the next).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Compute-shader and transfer writes made visible to later compute reads/writes, indirect-argument
// reads and fragment-shader reads: the barrier between chained compute passes.
void computeWriteBarrier(VkCommandBuffer cmd);

size_t formatBytesPerPixel(VkFormat format);

// Copies a 2D color image (RGBA32F, RGBA16F or RGBA8) to the CPU as RGBA floats (8-bit as 0..1).
// Synchronous; leaves the image in TRANSFER_SRC layout (the next transition moves it on).
std::vector<glm::vec4> readbackImage(VulkanContext& ctx, Image& image);
std::vector<uint8_t> readbackImageBytes(VulkanContext& ctx, Image& image);
// One mip level of a 2D or 3D colour image (RGBA32F, RGBA16F or RGBA8), x fastest, then y, then z.
std::vector<glm::vec4> readbackImageLevel(VulkanContext& ctx, Image& image, uint32_t level);
// Copies the first `count` elements of a device buffer to the CPU (synchronous: tests and tools).
template <class T>
std::vector<T> readbackBuffer(VulkanContext& ctx, VkBuffer source, size_t count);

std::vector<uint8_t> readbackBufferBytes(VulkanContext& ctx, VkBuffer source, VkDeviceSize bytes);
template <class T>
std::vector<T> readbackBuffer(VulkanContext& ctx, VkBuffer source, size_t count) {
  std::vector<T> out(count);
  if (count == 0) return out;
  const std::vector<uint8_t> bytes = readbackBufferBytes(ctx, source, VkDeviceSize(count) * sizeof(T));
  std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

}  // namespace dyngi::render
