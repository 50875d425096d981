#pragma once
// The sample's command line: one table of its own flags (scene, size, outputs, ...) and, for every GI
// setting, the option table of the technique the run uses (gi_module: OptionTable), so each name,
// default, range and help lives in one place. --help, --help-markdown (docs/OPTIONS.md) and the panel
// are generated from them. parseOptions never exits: it returns an error line for main to print.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/path_tracer.h"

namespace dyngi::sample {

constexpr int kHeadlessDefaultFrames = 60;  // a headless run without --frames

// The --gi values: "off", every registered technique by its registry name, and "path" (the reference).
const std::vector<std::string>& giModes();
// Whether `mode` is a registered technique (run by a GI system), not off or the reference.
bool isTechniqueMode(std::string_view mode);
// The views every technique has: the lit image and its indirect diffuse light before albedo.
const std::vector<std::string>& commonGiViews();
// The voxel scene's views, with any --gi (a voxel scene of its own when the technique has none).
const std::vector<std::string>& voxelViews();

struct Options {
  std::string scene = "cornell-dynamic";   // built-in name or a .gltf/.glb path
  bool headless = false;
  uint32_t width = 768, height = 768;
  int frames = -1;                          // -1: headless kHeadlessDefaultFrames, windowed until closed
  int warmup = -1;                          // frames left out of the --stats medians; -1: two, fewer for short runs
  // The warm-up this run uses: `warmup` when given, else 2 but always leaving one frame to time.
  int warmupFrames() const;
  std::string gi = "off";                   // a name from giModes()
  std::string animate;                      // a name from animatedSceneNames(), or none
  std::string out;                          // PNG of the last frame
  std::string hdrOut;                       // EXR, linear radiance before exposure
  std::string stats;                        // JSON
  std::string memoryLog;                    // TSV: every 100 frames, resident memory and live Vulkan allocations
  std::string view = "final";               // a common view, a voxel view or the technique's debug view
  std::string clip;                         // animation clip of a glTF scene (default: the first)
  std::string inputScript;                  // replayed clicks and keys (play/input.h), fixed time step
  std::string recordDir;                    // every frame's displayed image as DIR/frame_NNNNN.png
  std::string ui = "auto";                  // on | off | auto (on in a window, off headless): the settings panel
  std::string stageTimes = "timestamps";    // timestamps | fenced (render::GpuTimer::Mode)
  float exposure = 1.0f;
  // The whole frame's milliseconds to hold while a GI technique runs (play/frame_budget.h); -1: the
  // default, kWindowFrameBudgetMs in an interactive window unless a GI budget is given, else off. 0: off.
  float frameBudgetMs = -1.0f;
  static constexpr float kWindowFrameBudgetMs = 100.0f;
  // Scripted runs keep the default off: their frames must not depend on the machine's speed.
  double frameBudgetFor(bool interactiveWindow) const {
    if (frameBudgetMs >= 0.0f) return frameBudgetMs;
    return interactiveWindow && giSettings.budget.budgetMs == 0.0f ? kWindowFrameBudgetMs : 0.0;
  }
  bool validation = false;
  bool help = false;
  bool helpMarkdown = false;

  // GI settings, filled through the option tables: the technique's options (giSettings.technique is
  // `gi` when it names a technique), the voxel scene's, and the path tracer's for --gi path.
  gi::GiSettings giSettings;
  gi::PathTracerSettings pathTracer;
  bool usesGiSystem() const { return isTechniqueMode(gi); }
  bool showsUi() const { return ui == "on" || (ui == "auto" && !headless); }
};

std::string usage();
// docs/OPTIONS.md: every flag of the sample and every table option, as Markdown tables.
std::string usageMarkdown();
// Returns the options, or an error message in `error`.
std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error);
// Output files (--out, --hdr-out, --stats) go where they point: their directory must exist (nothing is
// created on the side) and the path must not be a directory. Checked before a run, so a long render
// never ends on a path it cannot write. Returns an error line, or "" when every path is usable.
std::string checkOutputPaths(const Options& o);

}  // namespace dyngi::sample
