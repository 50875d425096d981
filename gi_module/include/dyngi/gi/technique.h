#pragma once
// The contract every GI technique implements, and the registry that lists them.
//
// A technique is one folder, gi_module/techniques/<name>/: its options struct (the only place its
// defaults live; a table of names, ranges and help beside it), its render features, its shaders, and
// a small Technique class that GiSystem owns. The GI system hands it the shared services (the Embree
// BVH, the voxel scene when it asked for one) and, once a frame, the frame's change set and snapshot.
// How to add one: docs/ARCHITECTURE.md, "How to add a technique".
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dyngi/engine/render/render_feature.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/gi/budget_controller.h"
#include "dyngi/gi/change_set.h"
#include "dyngi/gi/options.h"

namespace dyngi::gi {

class EmbreeScene;
class VoxelScene;
struct GiSettings;

// What the GI system shares with every technique.
struct TechniqueServices {
  render::VulkanContext& ctx;
  const scene::AssetStore& assets;
  EmbreeScene* bvh;     // kept in sync with the world every frame, when the technique's entry asked for it
  VoxelScene* voxels;   // the voxel scene and its SVO, when the technique's entry asked for it
};

// The frame as the GI system saw it, handed to Technique::update.
struct TechniqueFrame {
  const ChangeSet& changes;
  const render::RenderSnapshot& snapshot;
};

class Technique {
 public:
  virtual ~Technique() = default;
  // CPU work once a frame, after the BVH and voxel updates (VPL invalidation and replacement).
  virtual void update(const TechniqueFrame& /*frame*/) {}
  // The render features it records, in order; the GI system attaches them after the voxel scene.
  virtual std::vector<render::RenderFeature*> features() = 0;
  // Its options as they are used (after rounding and clamping): the stats and the notices compare them
  // with what was asked.
  virtual std::vector<OptionRef> options() = 0;
  // Switches to one of its entry's debug views, or back to "final"; false for a name it does not have.
  virtual bool setDebugView(std::string_view /*name*/) { return false; }
  // The GPU sections it times (stats' stages_ms), as its features name them.
  virtual std::vector<const char*> timedSections() const = 0;
  // Its CPU sections' times of the last frame (stats' cpu_ms), e.g. VPL invalidation.
  virtual std::map<std::string, double> cpuMs() const { return {}; }
  // Its own figures for the stats JSON: section name -> (key -> value).
  virtual std::map<std::string, std::map<std::string, double>> statsSections() const { return {}; }
  // The knobs a GI budget (GiSettings::budget) may lower at run time, in the order they are lowered:
  // the one whose loss shows least first. Level 0 of each is its value in the technique's options.
  virtual std::vector<QualityKnob> qualityKnobs() { return {}; }
  // True when the frame just rendered did one-off work on top of its steady cost (the temporal
  // technique catching up several sets after a light switch): a GI budget leaves such frames out, so a
  // few heavy frames do not throw the knobs to their floor for the seconds it takes to climb back.
  virtual bool lastFrameWasOneOff() const { return false; }
  // While a GI budget holds the cost: one-off work is spread over frames instead (the temporal
  // technique catches up one set a frame; VCT traces its share of the pixels after a history drop), so
  // no frame costs several of the budget's.
  virtual void spreadOneOffWork(bool /*spread*/) {}
};

// One registered technique.
struct TechniqueEntry {
  const char* name;     // "temporal", "many-lights", "vct": the --gi value
  const char* summary;  // one line
  // Its debug views by name ("final", every technique's default, is not listed): known before it is made,
  // so a command line is checked before any device exists.
  std::vector<const char*> debugViews;
  // Its options struct inside GiSettings (what a command line or panel edits before it is made).
  std::vector<OptionRef> (*options)(GiSettings& settings);
  bool (*needsVoxels)(const GiSettings& settings);
  bool (*needsBvh)(const GiSettings& settings);  // rays on the CPU: the GI system keeps an Embree BVH only then
  std::unique_ptr<Technique> (*create)(const TechniqueServices& services, const GiSettings& settings);
};

// Every technique, in a stable order. Registered in gi_module/techniques/registry.cpp.
const std::vector<TechniqueEntry>& techniqueRegistry();
// The entry named `name`, or nullptr.
const TechniqueEntry* findTechnique(std::string_view name);

}  // namespace dyngi::gi
