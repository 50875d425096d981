#include "dyngi/engine/render/resources.h"

#include <cstring>
#include <utility>

#include <glm/gtc/packing.hpp>

namespace dyngi::render {

Buffer::Buffer(VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, const char* name)
    : ctx_(&ctx), size_(size) {
  try {
    create(usage, memory, name);
  } catch (...) {
    reset();
    throw;
  }
}

void Buffer::create(VkBufferUsageFlags usage, MemoryUsage memory, const char* name) {
  VulkanContext& ctx = *ctx_;
  const VkDeviceSize size = size_;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size ? size : 4;
  bci.usage = usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  DYNGI_VK(vkCreateBuffer(ctx.device(), &bci, ctx.allocator(), &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer_, &req);
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (memory) {
    case MemoryUsage::GpuOnly: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  uint32_t type = ctx.findMemoryType(req.memoryTypeBits, required, preferred);
  memory_ = ctx.allocateMemory(req, type, name);
  memoryBytes_ = req.size;
  memoryType_ = type;
  DYNGI_VK(vkBindBufferMemory(ctx.device(), buffer_, memory_, 0));
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mp);
  VkMemoryPropertyFlags flags = mp.memoryTypes[type].propertyFlags;
  if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    DYNGI_VK(vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
    coherent_ = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  }
  ctx.setName(VK_OBJECT_TYPE_BUFFER, uint64_t(buffer_), name);
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    memoryBytes_ = std::exchange(o.memoryBytes_, 0);
    memoryType_ = o.memoryType_;
    size_ = std::exchange(o.size_, 0);
    mapped_ = std::exchange(o.mapped_, nullptr);
    coherent_ = o.coherent_;
  }
  return *this;
}

void Buffer::reset() {
  if (!ctx_) return;
  if (buffer_) vkDestroyBuffer(ctx_->device(), buffer_, ctx_->allocator());
  ctx_->freeMemory(memory_, memoryBytes_, memoryType_);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  ctx_ = nullptr;
}

void Buffer::flush() {
  if (!mapped_ || coherent_) return;
  VkMappedMemoryRange r{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
  r.memory = memory_;
  r.offset = 0;
  r.size = VK_WHOLE_SIZE;
  vkFlushMappedMemoryRanges(ctx_->device(), 1, &r);
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw VulkanError("Buffer::upload out of range");
  if (mapped_) {
    std::memcpy(static_cast<uint8_t*>(mapped_) + offset, data, bytes);
    flush();
    return;
  }
  // Discrete GPUs: device-local memory is not mappable; copy through a staging buffer.
  Buffer staging(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging");
  std::memcpy(staging.mapped(), data, bytes);
  VkBuffer dst = buffer_;
  ctx_->immediate([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.handle(), dst, 1, &copy);
  });
}

void Buffer::invalidateForRead() {
  if (!mapped_ || coherent_) return;
  VkMappedMemoryRange r{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
  r.memory = memory_;
  r.size = VK_WHOLE_SIZE;
  vkInvalidateMappedMemoryRanges(ctx_->device(), 1, &r);
}

static bool isDepthFormat(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

VkImageAspectFlags Image::aspect() const {
  return isDepthFormat(desc_.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

Image::Image(VulkanContext& ctx, const ImageDesc& desc) : ctx_(&ctx), desc_(desc) {
  try {
    create();
  } catch (...) {
    reset();
    throw;
  }
}

void Image::create() {
  VulkanContext& ctx = *ctx_;
  const ImageDesc& desc = desc_;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  const bool volume = desc.viewType == VK_IMAGE_VIEW_TYPE_3D;
  ici.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ici.format = desc.format;
  ici.extent = {std::max(desc.width, 1u), std::max(desc.height, 1u), volume ? std::max(desc.depth, 1u) : 1u};
  ici.mipLevels = desc.mips;
  ici.arrayLayers = desc.layers;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = desc.usage;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (desc.viewType == VK_IMAGE_VIEW_TYPE_CUBE || desc.viewType == VK_IMAGE_VIEW_TYPE_CUBE_ARRAY)
    ici.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
  DYNGI_VK(vkCreateImage(ctx.device(), &ici, ctx.allocator(), &image_));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device(), image_, &req);
  memoryType_ = ctx.findMemoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  memory_ = ctx.allocateMemory(req, memoryType_, desc.name);
  memoryBytes_ = req.size;
  DYNGI_VK(vkBindImageMemory(ctx.device(), image_, memory_, 0));

  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = image_;
  vci.viewType = desc.viewType;
  vci.format = desc.format;
  vci.subresourceRange = {aspect(), 0, desc.mips, 0, desc.layers};
  DYNGI_VK(vkCreateImageView(ctx.device(), &vci, ctx.allocator(), &view_));
  if (desc.layers > 1) {
    for (uint32_t l = 0; l < desc.layers; ++l) {
      vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
      vci.subresourceRange = {aspect(), 0, 1, l, 1};
      VkImageView v;
      DYNGI_VK(vkCreateImageView(ctx.device(), &vci, ctx.allocator(), &v));
      layerViews_.push_back(v);
    }
  } else {
    layerViews_.push_back(view_);
  }
  if (desc.mips > 1) {
    for (uint32_t m = 0; m < desc.mips; ++m) {
      vci.viewType = desc.viewType;
      vci.subresourceRange = {aspect(), m, 1, 0, desc.layers};
      VkImageView v;
      DYNGI_VK(vkCreateImageView(ctx.device(), &vci, ctx.allocator(), &v));
      mipViews_.push_back(v);
    }
  } else {
    mipViews_.push_back(view_);
  }
  ctx.setName(VK_OBJECT_TYPE_IMAGE, uint64_t(image_), desc.name);
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    image_ = std::exchange(o.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    memoryBytes_ = std::exchange(o.memoryBytes_, 0);
    memoryType_ = o.memoryType_;
    view_ = std::exchange(o.view_, VK_NULL_HANDLE);
    layerViews_ = std::move(o.layerViews_);
    o.layerViews_.clear();
    mipViews_ = std::move(o.mipViews_);
    o.mipViews_.clear();
    desc_ = o.desc_;
    layout_ = o.layout_;
    lastStage_ = o.lastStage_;
    lastAccess_ = o.lastAccess_;
  }
  return *this;
}

void Image::reset() {
  if (!ctx_) return;
  VkDevice d = ctx_->device();
  for (VkImageView v : layerViews_)
    if (v != view_) vkDestroyImageView(d, v, ctx_->allocator());
  layerViews_.clear();
  for (VkImageView v : mipViews_)
    if (v != view_) vkDestroyImageView(d, v, ctx_->allocator());
  mipViews_.clear();
  if (view_) vkDestroyImageView(d, view_, ctx_->allocator());
  if (image_) vkDestroyImage(d, image_, ctx_->allocator());
  ctx_->freeMemory(memory_, memoryBytes_, memoryType_);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
  layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
}

void Image::transition(VkCommandBuffer cmd, VkImageLayout newLayout, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  imageBarrier(cmd, image_, {aspect(), 0, desc_.mips, 0, desc_.layers}, layout_, newLayout, lastStage_, lastAccess_, dstStage, dstAccess);
  layout_ = newLayout;
  lastStage_ = dstStage;
  lastAccess_ = dstAccess;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = range;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void computeWriteBarrier(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT |
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

Image createTexture(VulkanContext& ctx, uint32_t width, uint32_t height, const uint8_t* rgba8, bool srgb, const char* name) {
  ImageDesc d;
  d.width = width;
  d.height = height;
  d.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  d.name = name;
  Image img(ctx, d);
  VkDeviceSize bytes = VkDeviceSize(width) * height * 4;
  Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "texture staging");
  std::memcpy(staging.mapped(), rgba8, bytes);
  ctx.immediate([&](VkCommandBuffer cmd) {
    img.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), img.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    img.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  return img;
}

size_t formatBytesPerPixel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT: return 16;
    default: return 0;
  }
}

namespace {
VkExtent3D levelExtent(const ImageDesc& d, uint32_t level) {
  const uint32_t depth = d.viewType == VK_IMAGE_VIEW_TYPE_3D ? d.depth : 1u;
  return {std::max(d.width >> level, 1u), std::max(d.height >> level, 1u), std::max(depth >> level, 1u)};
}

Buffer copyToHost(VulkanContext& ctx, Image& img, uint32_t level = 0) {
  size_t bpp = formatBytesPerPixel(img.desc().format);
  if (bpp == 0) throw VulkanError("readback: unsupported format");
  if (level >= img.desc().mips) throw VulkanError("readback: no such mip level");
  const VkExtent3D e = levelExtent(img.desc(), level);
  VkDeviceSize bytes = VkDeviceSize(e.width) * e.height * e.depth * bpp;
  Buffer out(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "readback");
  ctx.immediate([&](VkCommandBuffer cmd) {
    img.transition(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
    region.imageExtent = e;
    vkCmdCopyImageToBuffer(cmd, img.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.handle(), 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  out.invalidateForRead();
  return out;
}
}  // namespace

std::vector<glm::vec4> readbackImage(VulkanContext& ctx, Image& img) { return readbackImageLevel(ctx, img, 0); }

std::vector<glm::vec4> readbackImageLevel(VulkanContext& ctx, Image& img, uint32_t level) {
  Buffer buf = copyToHost(ctx, img, level);
  const VkExtent3D e = levelExtent(img.desc(), level);
  size_t n = size_t(e.width) * e.height * e.depth;
  std::vector<glm::vec4> out(n);
  const uint8_t* src = static_cast<const uint8_t*>(buf.mapped());
  switch (img.desc().format) {
    case VK_FORMAT_R32G32B32A32_SFLOAT: std::memcpy(out.data(), src, n * 16); break;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      for (size_t i = 0; i < n; ++i) {
        uint16_t h[4];
        std::memcpy(h, src + i * 8, 8);
        out[i] = glm::vec4(glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]), glm::unpackHalf1x16(h[3]));
      }
      break;
    case VK_FORMAT_R8G8B8A8_UNORM:
      for (size_t i = 0; i < n; ++i) out[i] = glm::vec4(src[i * 4], src[i * 4 + 1], src[i * 4 + 2], src[i * 4 + 3]) / 255.0f;
      break;
    case VK_FORMAT_R8G8B8A8_SNORM:
      for (size_t i = 0; i < n; ++i) {
        int8_t b[4];
        std::memcpy(b, src + i * 4, 4);
        out[i] = glm::max(glm::vec4(b[0], b[1], b[2], b[3]) / 127.0f, glm::vec4(-1.0f));
      }
      break;
    default: throw VulkanError("readback: unsupported format");
  }
  return out;
}

std::vector<uint8_t> readbackImageBytes(VulkanContext& ctx, Image& img) {
  Buffer buf = copyToHost(ctx, img);
  const uint8_t* src = static_cast<const uint8_t*>(buf.mapped());
  return std::vector<uint8_t>(src, src + buf.size());
}

std::vector<uint8_t> readbackBufferBytes(VulkanContext& ctx, VkBuffer source, VkDeviceSize bytes) {
  Buffer host(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "buffer readback");
  ctx.immediate([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(cmd, source, host.handle(), 1, &copy);
  });
  host.invalidateForRead();
  const uint8_t* p = static_cast<const uint8_t*>(host.mapped());
  return std::vector<uint8_t>(p, p + bytes);
}

}  // namespace dyngi::render
