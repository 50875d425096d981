#pragma once
// The sample's command line. Its own flags (scene, size, outputs, ...) are written here; every GI
// setting comes from the option tables of the technique the run uses (gi_module: OptionTable), so its
// name, default, range and help live in one place. parseOptions never exits: it returns an error line
// for main to print.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/path_tracer.h"

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
  std::string vplSource = "paths";          // paths (incremental, temporal) | rsm (per frame, svo only)
  std::string animate;                      // static | moving-spot | rotating-object | moving-camera | walking-fox | fox-and-spot
  std::string out;                          // PNG of the last frame
  std::string hdrOut;                       // EXR, linear radiance before exposure
  std::string stats;                        // JSON
  std::string memoryLog;                    // TSV: every 100 frames, resident memory and live Vulkan allocations
  std::string view = "final";               // final | voxels | svo-steps | a technique's debug view
  std::string clip;                         // animation clip of a glTF scene (default: the first)
  std::string inputScript;                  // --input-script: replayed clicks and keys (play/input.h), fixed time step
  std::string recordDir;                    // --record: every frame's displayed image as DIR/frame_NNNNN.png
  std::string ui = "auto";                  // on | off | auto (on in a window, off headless): the settings panel
  std::string stageTimes = "timestamps";    // --stage-times: timestamps | fenced (render::GpuTimer::Mode)
  float exposure = 1.0f;
  bool validation = false;
  bool help = false;

  // GI settings, filled through the option tables: the technique's options (giSettings.technique
  // names it; "" for --gi off and path), the voxel scene's, and the path tracer's for --gi path.
  gi::GiSettings giSettings;
  gi::PathTracerSettings pathTracer;
  bool usesGiSystem() const { return gi == "svo" || gi == "bvh" || gi == "vct"; }
  bool showsUi() const { return ui == "on" || (ui == "auto" && !headless); }
};

std::string usage();
// Returns the options, or an error message in `error`.
std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error);
// Output files (--out, --hdr-out, --stats) go where they point: their directory must exist (nothing is
// created on the side) and the path must not be a directory. Checked before a run, so a long render
// never ends on a path it cannot write. Returns an error line, or "" when every path is usable.
std::string checkOutputPaths(const Options& o);

}  // namespace dyngi::sample
