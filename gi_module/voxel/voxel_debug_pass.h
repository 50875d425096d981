#pragma once
// The voxel scene's debug views ("voxel_debug_view" in stats), replacing the final image: the first
// voxel hit per pixel coloured by its leaf's albedo (voxels), or the SVO-restart march's step count
// (svo-steps).
#include "dyngi/engine/render/frame_context.h"
#include "dyngi/engine/render/pipeline.h"
#include "dyngi/gi/voxel.h"
#include "dyngi/gi/voxel_scene.h"

namespace dyngi::gi {

class VoxelDebugPass {
 public:
  explicit VoxelDebugPass(render::VulkanContext& ctx);
  void record(render::FrameContext& frame, const VoxelScene& voxels, VoxelDebugView view);

 private:
  render::VulkanContext& ctx_;
  render::LazyPipeline pipeline_;  // made on first use: a debug view
};

}  // namespace dyngi::gi
