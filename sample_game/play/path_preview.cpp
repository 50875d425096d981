#include "play/path_preview.h"

#include "dyngi/engine/render/frame_context.h"

namespace dyngi::sample {

PathPreview::PathPreview(const gi::EmbreeScene& bvh, const scene::AssetStore& assets, const gi::PathTracerSettings& settings)
    : bvh_(bvh), assets_(assets), settings_(settings) {
  settings_.spp = 1;  // a frame's worth; the mean accumulates over frames
}

void PathPreview::resize(render::VulkanContext&, uint32_t width, uint32_t height) {
  width_ = width;
  height_ = height;
  spp_ = 0;
  staging_.reset();
}

void PathPreview::prepare(render::VulkanContext& ctx, const render::RenderSnapshot& snapshot) {
  if (width_ == 0 || height_ == 0) return;
  // The state the picture depends on, flattened: equal to last frame's means the mean goes on.
  std::vector<glm::mat4> models;
  std::vector<glm::vec4> materials, lights;
  for (const render::DrawItem& d : snapshot.draws) {
    models.push_back(d.model);
    const scene::Material& m = snapshot.materialOf(d);
    materials.push_back(m.baseColor);
    materials.push_back(glm::vec4(m.emissive, m.roughness));
  }
  for (const render::LightItem& l : snapshot.lights) {
    lights.push_back(glm::vec4(l.position, l.light.intensity * float(l.light.enabled)));
    lights.push_back(glm::vec4(l.direction, l.light.outerConeAngle));
    lights.push_back(glm::vec4(l.light.color, l.light.innerConeAngle));
  }
  if (snapshot.camera.view != view_ || models != models_ || materials != materials_ || lights != lights_) {
    spp_ = 0;
    view_ = snapshot.camera.view;
    models_ = std::move(models);
    materials_ = std::move(materials);
    lights_ = std::move(lights);
  }
  if (spp_ == 0) sum_.assign(size_t(width_) * height_, glm::vec4(0.0f));
  gi::PathTracerSettings s = settings_;
  s.seed = settings_.seed + spp_;  // a new sample per pixel each frame
  const render::ImageRgba frame = gi::pathTrace(snapshot, bvh_, assets_, width_, height_, s);
  for (size_t i = 0; i < sum_.size(); ++i) sum_[i] += frame[i];
  ++spp_;
  const VkDeviceSize bytes = VkDeviceSize(sum_.size() * sizeof(glm::vec4));
  if (!staging_) staging_ = std::make_unique<render::Buffer>(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, render::MemoryUsage::Upload, "path preview");
  std::vector<glm::vec4> mean(sum_.size());
  for (size_t i = 0; i < sum_.size(); ++i) mean[i] = sum_[i] / float(spp_);
  staging_->upload(mean.data(), bytes);
}

void PathPreview::recordAfterLighting(render::FrameContext& frame) {
  if (!staging_ || spp_ == 0 || frame.targets.width != width_) return;
  render::Image& hdr = frame.targets.hdr;
  render::ScopedPass scope(frame.ctx, frame.timer, frame.cmd, "path_preview");
  hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  vkCmdCopyBufferToImage(frame.cmd, staging_->handle(), hdr.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  hdr.transition(frame.cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
}

}  // namespace dyngi::sample
