#include "indirect/reduced_screen.h"

#include <cmath>

#include "indirect/shaders/indirect_shared.h"
#include "spirv/reduce_gbuffer.comp.spv.h"
#include "spirv/upsample_indirect.comp.spv.h"

#include "gpu_aliases.h"

namespace dyngi::gi {

::dyngi::gpu::FrameUniforms reducedUniforms(const ::dyngi::gpu::FrameUniforms& full, float scale) {
  ::dyngi::gpu::FrameUniforms r = full;
  const uint32_t W = full.sizeAndCount.x, H = full.sizeAndCount.y;
  const uint32_t w = ReducedScreen::reducedSize(W, scale), h = ReducedScreen::reducedSize(H, scale);
  r.sizeAndCount.x = w;
  r.sizeAndCount.y = h;
  // Reduced pixel q's centre is the full-resolution point c = (q + 0.5) s; the frame's ray there is
  // pixelRay0 + (c - 0.5) step (pixelRay0 is through pixel 0's centre, 0.5).
  const float sx = float(double(W) / w), sy = float(double(H) / h);
  r.pixelRay0 = full.pixelRay0 + (0.5f * sx - 0.5f) * full.pixelRayStepX + (0.5f * sy - 0.5f) * full.pixelRayStepY;
  r.pixelRayStepX = sx * full.pixelRayStepX;
  r.pixelRayStepY = sy * full.pixelRayStepY;
  return r;
}

QualityKnob gatherFractionKnob(std::function<void(float)> setFactor) {
  std::vector<double> levels;
  for (double f = 1.0; f > 1.0 / 16.0 + 1e-9; f *= kBudgetStepRatio) levels.push_back(f);
  levels.push_back(1.0 / 16.0);
  return {"gather_fraction", levels, [set = std::move(setFactor)](double v) { set(float(1.0 / std::sqrt(std::max(v, 1e-6)))); }};
}

void ReducedScreen::makeTargets(uint32_t width, uint32_t height) {
  auto make = [&](VkFormat f, const char* name) {
    render::ImageDesc d;
    d.width = width;
    d.height = height;
    d.format = f;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.name = name;
    return Image(ctx_, d);
  };
  targets_ = {};
  targets_.width = width;
  targets_.height = height;
  targets_.position = make(VK_FORMAT_R32G32B32A32_SFLOAT, "reduced position");
  targets_.normal = make(VK_FORMAT_R16G16B16A16_SFLOAT, "reduced normal");
  targets_.albedo = make(VK_FORMAT_R8G8B8A8_UNORM, "reduced albedo");
  targets_.emissive = make(VK_FORMAT_R16G16B16A16_SFLOAT, "reduced emissive");
  targets_.indirect = make(VK_FORMAT_R32G32B32A32_SFLOAT, "reduced indirect");
}

render::FrameContext& ReducedScreen::begin(render::FrameContext& frame, float scale) {
  const render::RenderTargets& t = frame.targets;
  const uint32_t w = reducedSize(t.width, scale), h = reducedSize(t.height, scale);
  scale_ = glm::vec2(float(double(t.width) / w), float(double(t.height) / h));
  frame_.reset();
  if (!reduces(t.width, t.height, scale)) return frame;
  if (targets_.width != w || targets_.height != h) makeTargets(w, h);
  if (!uniformBuffer_.valid())
    uniformBuffer_ = Buffer(ctx_, sizeof(::dyngi::gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Upload, "reduced frame uniforms");
  uniforms_ = reducedUniforms(frame.uniforms, scale);
  uniformBuffer_.upload(&uniforms_, sizeof(uniforms_));
  if (!reduce_.handle()) {
    const Binding b[] = {{DYNGI_REDUCE_BINDING_POSITION, kStorageImage, kCS},     {DYNGI_REDUCE_BINDING_NORMAL, kStorageImage, kCS},
                         {DYNGI_REDUCE_BINDING_ALBEDO, kStorageImage, kCS},       {DYNGI_REDUCE_BINDING_EMISSIVE, kStorageImage, kCS},
                         {DYNGI_REDUCE_BINDING_OUT_POSITION, kStorageImage, kCS}, {DYNGI_REDUCE_BINDING_OUT_NORMAL, kStorageImage, kCS},
                         {DYNGI_REDUCE_BINDING_OUT_ALBEDO, kStorageImage, kCS},   {DYNGI_REDUCE_BINDING_OUT_EMISSIVE, kStorageImage, kCS}};
    reduce_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_reduce_gbuffer_comp), b, sizeof(gpu::ReducedScreenPush), "reduce_gbuffer");
  }
  {
    render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "reduce");
    VkCommandBuffer cmd = frame.cmd;
    render::RenderTargets& full = frame.targets;
    for (Image* img : {&full.position, &full.normal, &full.albedo, &full.emissive})
      img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    for (Image* img : {&targets_.position, &targets_.normal, &targets_.albedo, &targets_.emissive})
      img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reduce_.handle());
    DescriptorWrites()
        .storageImage(DYNGI_REDUCE_BINDING_POSITION, full.position.view())
        .storageImage(DYNGI_REDUCE_BINDING_NORMAL, full.normal.view())
        .storageImage(DYNGI_REDUCE_BINDING_ALBEDO, full.albedo.view())
        .storageImage(DYNGI_REDUCE_BINDING_EMISSIVE, full.emissive.view())
        .storageImage(DYNGI_REDUCE_BINDING_OUT_POSITION, targets_.position.view())
        .storageImage(DYNGI_REDUCE_BINDING_OUT_NORMAL, targets_.normal.view())
        .storageImage(DYNGI_REDUCE_BINDING_OUT_ALBEDO, targets_.albedo.view())
        .storageImage(DYNGI_REDUCE_BINDING_OUT_EMISSIVE, targets_.emissive.view())
        .push(ctx_, cmd, reduce_);
    const gpu::ReducedScreenPush pc{scale_.x, scale_.y};
    vkCmdPushConstants(cmd, reduce_.layout(), kCS, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, dispatchGroups(w, 8), dispatchGroups(h, 8), 1);
  }
  frame_.emplace(render::FrameContext{frame.ctx, frame.cmd, frame.timer, frame.snapshot, targets_, uniformBuffer_, uniforms_, frame.meshes,
                                      frame.linearSampler, frame.nearestSampler, frame.textureView, frame.submitAndWait, frame.lights,
                                      frame.instances, frame.specular});
  return *frame_;
}

void ReducedScreen::finish(render::FrameContext& frame) {
  if (!frame_) return;
  if (!upsample_.handle()) {
    const Binding b[] = {{DYNGI_UPSAMPLE_BINDING_FRAME, kUBO, kCS},
                         {DYNGI_UPSAMPLE_BINDING_POSITION, kStorageImage, kCS},
                         {DYNGI_UPSAMPLE_BINDING_NORMAL, kStorageImage, kCS},
                         {DYNGI_UPSAMPLE_BINDING_LOW_POSITION, kStorageImage, kCS},
                         {DYNGI_UPSAMPLE_BINDING_LOW_NORMAL, kStorageImage, kCS},
                         {DYNGI_UPSAMPLE_BINDING_LOW_INDIRECT, kStorageImage, kCS},
                         {DYNGI_UPSAMPLE_BINDING_OUT_INDIRECT, kStorageImage, kCS}};
    upsample_ = Pipeline::compute(ctx_, DYNGI_SHADER(spv_upsample_indirect_comp), b, sizeof(gpu::ReducedScreenPush), "upsample_indirect");
  }
  render::ScopedPass scope(ctx_, frame.timer, frame.cmd, "upsample");
  VkCommandBuffer cmd = frame.cmd;
  render::RenderTargets& full = frame.targets;
  for (Image* img : {&targets_.position, &targets_.normal, &targets_.indirect})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  for (Image* img : {&full.position, &full.normal})
    img->transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  full.indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, upsample_.handle());
  DescriptorWrites()
      .uniformBuffer(DYNGI_UPSAMPLE_BINDING_FRAME, frame.frameUniforms.handle())
      .storageImage(DYNGI_UPSAMPLE_BINDING_POSITION, full.position.view())
      .storageImage(DYNGI_UPSAMPLE_BINDING_NORMAL, full.normal.view())
      .storageImage(DYNGI_UPSAMPLE_BINDING_LOW_POSITION, targets_.position.view())
      .storageImage(DYNGI_UPSAMPLE_BINDING_LOW_NORMAL, targets_.normal.view())
      .storageImage(DYNGI_UPSAMPLE_BINDING_LOW_INDIRECT, targets_.indirect.view())
      .storageImage(DYNGI_UPSAMPLE_BINDING_OUT_INDIRECT, full.indirect.view())
      .push(ctx_, cmd, upsample_);
  const gpu::ReducedScreenPush pc{scale_.x, scale_.y};
  vkCmdPushConstants(cmd, upsample_.layout(), kCS, 0, sizeof(pc), &pc);
  vkCmdDispatch(cmd, dispatchGroups(full.width, 8), dispatchGroups(full.height, 8), 1);
  frame.specular = frame_->specular;
}

}  // namespace dyngi::gi
