#pragma once
// The camera part of the per-frame uniforms every pass sees (shared/gpu_types.h: FrameUniforms).
#include <cstdint>

#include "dyngi/engine/render/snapshot.h"
#include "shared/gpu_types.h"

namespace dyngi::render {

// view, proj, viewProj, invViewProj, cameraPos and the pixel rays for a width x height target; the
// other members are left zero for the renderer to fill.
gpu::FrameUniforms cameraUniforms(const CameraView& camera, uint32_t width, uint32_t height);

}  // namespace dyngi::render
