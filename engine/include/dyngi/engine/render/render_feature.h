#pragma once
// The hook through which a subsystem (dyngi's GI, or a user's own effect) adds GPU work to the frame
// without the engine knowing about it. A feature records after the G-buffer and shadow maps and before
// lighting; it reads the G-buffer and writes targets.indirect (or its own images), which lighting
// multiplies by albedo and adds to direct light.
#include "dyngi/engine/render/frame_context.h"

namespace dyngi::render {

class RenderFeature {
 public:
  virtual ~RenderFeature() = default;
  virtual const char* name() const = 0;
  // CPU work before recording (uploads, culling). Called once per frame.
  virtual void prepare(VulkanContext& /*ctx*/, const RenderSnapshot& /*snapshot*/) {}
  // Records GPU work. Returns true when it wrote targets.indirect this frame (else it is cleared).
  virtual bool record(FrameContext& frame) = 0;
  // Records after lighting, before tone mapping: debug views that replace targets.hdr.
  virtual void recordAfterLighting(FrameContext& /*frame*/) {}
  // Records after tone mapping: draws over the display image (targets.ldr: RGBA8 UNORM holding
  // sRGB-encoded values, GENERAL layout before and after), e.g. a user interface. What it draws is in
  // the presented image and in readbackLdr().
  virtual void recordOverlay(FrameContext& /*frame*/) {}
  // Called after the frame's fence: read back results, resolve queries.
  virtual void frameFinished(VulkanContext& /*ctx*/) {}
  // Called when the render targets are recreated (resize).
  virtual void resize(VulkanContext& /*ctx*/, uint32_t /*width*/, uint32_t /*height*/) {}
};

}  // namespace dyngi::render
