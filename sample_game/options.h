#pragma once
// The sample's command line. parseOptions never exits: it returns an error line for main to print.
#include <cstdint>
#include <optional>
#include <string>

namespace dyngi::sample {

constexpr int kHeadlessDefaultFrames = 60;  // a headless run without --frames

struct Options {
  std::string scene = "cornell-dynamic";   // built-in name or a .gltf/.glb path
  bool headless = false;
  uint32_t width = 768, height = 768;
  int frames = -1;                          // -1: headless kHeadlessDefaultFrames, windowed until closed
  int warmup = -1;                          // frames left out of the --stats medians (pipeline compiles,
                                            // filling); -1: two, or fewer when the run is shorter
  // The warm-up this run uses: `warmup` when given, else 2 but always leaving one frame to time.
  int warmupFrames() const;
  std::string gi = "off";                   // off | svo | bvh | path
  uint32_t temporal = 16;                   // T temporal VPL sets (svo/bvh with path VPLs)
  uint32_t reshoot = 0;                     // VPLs reshot per frame (0: vpls / T)
  std::string vplSource = "paths";          // paths (incremental, temporal) | rsm (per frame, svo only)
  std::string animate;                      // static | moving-spot | rotating-object | moving-camera | walking-fox | fox-and-spot
  uint32_t vpls = 512;                      // many-lights VPL count
  uint32_t interleave = 4;                  // many-lights K (K x K sub-images)
  float distanceClamp = 0.01f;              // many-lights B (world units^2)
  uint32_t spp = 64;                        // path tracer samples per pixel
  uint32_t bounces = 1;                     // indirect bounces (path tracer; later the GI techniques)
  std::string out;                          // PNG of the last frame
  std::string hdrOut;                       // EXR, linear radiance before exposure
  std::string stats;                        // JSON
  std::string memoryLog;                    // TSV: every 100 frames, resident memory and live Vulkan allocations
  std::string view = "final";               // final | voxels | svo-steps | indirect | vpls | subimages
  uint32_t voxelResolution = 128;           // voxel volume resolution (power of two, 64..512)
  std::string clip;                         // animation clip of a glTF scene (default: the first)
  uint32_t seed = 1;                        // random sequences (path tracer, VPLs)
  float exposure = 1.0f;
  bool validation = false;
  bool help = false;
};

std::string usage();
// Returns the options, or an error message in `error`.
std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error);
// Output files (--out, --hdr-out, --stats) go where they point: their directory must exist (nothing is
// created on the side) and the path must not be a directory. Checked before a run, so a long render
// never ends on a path it cannot write. Returns an error line, or "" when every path is usable.
std::string checkOutputPaths(const Options& o);

}  // namespace dyngi::sample
