#include "dyngi/gi/gi_system.h"

#include <cmath>
#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/components.h"
#include "gi_views.h"

namespace dyngi::gi {

// The GI system's first render feature: hands the renderer's snapshot to the technique's CPU update
// before any GI feature prepares.
class GiFrameUpdate final : public render::RenderFeature {
 public:
  explicit GiFrameUpdate(GiSystem& gi) : gi_(gi) {}
  const char* name() const override { return "gi_frame_update"; }
  void prepare(render::VulkanContext&, const render::RenderSnapshot& snapshot) override { gi_.updateTechnique(snapshot); }
  void frameFinished(render::VulkanContext&) override { gi_.frameTimed(); }
  bool record(render::FrameContext&) override { return false; }

 private:
  GiSystem& gi_;
};

GiSystem::GiSystem(render::VulkanContext& ctx, const scene::AssetStore& assets, const GiSettings& s) : ctx_(ctx), assets_(assets) {
  build(s);
}

GiSystem::~GiSystem() = default;

void GiSystem::build(const GiSettings& s) {
  const TechniqueEntry* entry = findTechnique(s.technique);
  if (!entry) throw std::invalid_argument("unknown GI technique '" + s.technique + "'");
  // The old parts go first, users before what they use (the technique holds the BVH and voxel scene).
  budget_.reset();
  frameUpdate_.reset();
  indirectView_.reset();
  technique_.reset();
  voxelSync_.reset();
  voxels_.reset();
  bvh_.reset();
  entry_ = entry;
  settings_ = s;
  changes_ = ChangeTracker{};
  pending_ = ChangeSet{};
  giMs_ = -1;
  if (entry_->needsBvh(s)) bvh_ = std::make_unique<EmbreeScene>();
  if (entry_->needsVoxels(s)) {
    // The VPL techniques march the nodes only; the voxel debug view turns attributes on when asked.
    VoxelSettings vs = s.voxels;
    vs.leafAttributes = false;
    voxels_ = std::make_unique<VoxelScene>(ctx_, vs);
    voxelSync_ = std::make_unique<VoxelSyncSystem>(*voxels_, assets_);
  }
  technique_ = entry_->create(TechniqueServices{ctx_, assets_, bvh_.get(), voxels_.get()}, s);
  frameUpdate_ = std::make_unique<GiFrameUpdate>(*this);
  indirectView_ = std::make_unique<GiIndirectView>(ctx_);
  if (view_ != "final" && !setDebugView(view_)) view_ = "final";  // the same view after a rebuild, when it still exists
  if (s.budget.budgetMs > 0.0f) budget_ = std::make_unique<BudgetController>(s.budget.budgetMs, technique_->qualityKnobs());
  spreadOneOffWork(budget_ != nullptr);
}

void GiSystem::spreadOneOffWork(bool spread) {
  technique_->spreadOneOffWork(spread);
  if (voxels_) voxels_->setSpreadVoxelization(spread);
}

void GiSystem::setBudgetMs(double budgetMs) {
  settings_.budget.budgetMs = std::isfinite(budgetMs) && budgetMs > 0.0 ? float(budgetMs) : 0.0f;
  if (settings_.budget.budgetMs == 0.0f) {
    if (budget_)
      for (const QualityKnob& k : budget_->knobs())
        if (k.apply && !k.levels.empty()) k.apply(k.levels.front());
    budget_.reset();
    spreadOneOffWork(false);
    return;
  }
  if (budget_) budget_->setBudgetMs(settings_.budget.budgetMs);
  else budget_ = std::make_unique<BudgetController>(settings_.budget.budgetMs, technique_->qualityKnobs());
  spreadOneOffWork(true);
}

void GiSystem::attach(render::Renderer& renderer) {
  if (detached_) {  // it missed every change while detached
    build(settings_);
    startOver_ = true;
    detached_ = false;
  }
  renderer_ = &renderer;
  addFeaturesTo(renderer);
}

void GiSystem::detach() {
  if (!renderer_) return;
  removeFeaturesFrom(*renderer_);
  renderer_ = nullptr;
  detached_ = true;
}

void GiSystem::addFeaturesTo(render::Renderer& renderer) {
  renderer.addFeature(frameUpdate_.get());
  if (voxels_) renderer.addFeature(voxels_.get());
  for (render::RenderFeature* f : technique_->features()) renderer.addFeature(f);
  renderer.addFeature(indirectView_.get());
}

void GiSystem::removeFeaturesFrom(render::Renderer& renderer) {
  renderer.removeFeature(frameUpdate_.get());
  if (voxels_) renderer.removeFeature(voxels_.get());
  for (render::RenderFeature* f : technique_->features()) renderer.removeFeature(f);
  renderer.removeFeature(indirectView_.get());
}

void GiSystem::reset(const GiSettings& settings) {
  if (!findTechnique(settings.technique)) throw std::invalid_argument("unknown GI technique '" + settings.technique + "'");
  if (renderer_) removeFeaturesFrom(*renderer_);
  build(settings);
  if (renderer_) addFeaturesTo(*renderer_);
  startOver_ = true;
  detached_ = false;  // rebuilt from the whole world: attach() need not build again
}

void GiSystem::run(ecs::World& world, const ecs::SystemContext& ctx) {
  if (detached_) return;
  auto t0 = std::chrono::steady_clock::now();
  // 1. What changed since the last run, once, from the change ticks (no scan of the world); every
  //    consumer below reads this one set.
  //    After reset() the new parts start from an empty world: everything is new (tick 0), as on a first run.
  const ChangeSet changes = changes_.compute(world, assets_, startOver_ ? 0 : ctx.lastRun);
  startOver_ = false;
  // 2. BVH (for a technique that traces rays on the CPU): instance transforms, refits, added/removed.
  if (bvh_) bvh_->sync(world, assets_, changes);
  // 3. Voxels: mark what must be re-voxelized (the GPU work is recorded by the VoxelScene feature).
  if (voxelSync_) voxelSync_->apply(changes);
  // 4. The technique's CPU work waits for the renderer's snapshot (updateTechnique).
  pending_.merge(changes);
  syncMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<const char*> GiSystem::timedSections() const {
  std::vector<const char*> names;
  if (voxels_) names = VoxelScene::timedSections();
  for (const char* n : technique_->timedSections()) names.push_back(n);
  return names;
}

double GiSystem::measureLastFrame() const { return renderer_ ? giCost(renderer_->lastStats().gpuMs) : -1; }

double GiSystem::giCost(const std::vector<std::pair<std::string, double>>& gpuMs) const {
  const std::vector<const char*> sections = timedSections();
  double ms = 0;
  bool timed = false;
  for (const auto& [name, sectionMs] : gpuMs)
    for (const char* s : sections)
      if (name == s) ms += sectionMs, timed = true;
  if (!timed) return -1;  // no frame rendered yet, or timestamps off
  for (const auto& [name, cpuMs] : technique_->cpuMs()) ms += cpuMs;
  return ms;
}

void GiSystem::frameTimed() {
  giMs_ = measureLastFrame();
  if (!budget_ || giMs_ < 0) return;
  const bool oneOff = technique_->lastFrameWasOneOff();
  if (!oneOff) budget_->onFrame(giMs_);
  checkTiming(oneOff);
}

// A budget held on timestamps that do not bracket the GI's work would hold a cost the device does not
// spend. After a few frames, a few frames are fenced (each section waited for and timed on the CPU) with
// the timestamps written beside the fences: the same work seen both ways. When the timestamps hold less
// than kMinTimestampCoverage of the fenced cost, every later frame is fenced. A host's frames cannot
// be fenced: they keep the timestamps, unchecked.
void GiSystem::checkTiming(bool oneOffFrame) {
  using Mode = render::GpuTimer::Mode;
  TimingCheck& t = timing_;
  if (!renderer_ || !renderer_->stageTiming() || renderer_->hostRecordsFrames()) return;
  if (t.checking) {
    const double stamped = giCost(renderer_->lastStats().gpuMsTimestamps);
    if (oneOffFrame || stamped < 0) return;  // not a measure (or no timestamps beside the fences): the next frame
    t.fencedMs += giMs_;
    t.stampedMs += stamped;
    if (++t.framesChecked < TimingCheck::kFencedFrames) return;
    t.checking = false;
    t.coverage = t.stampedMs / std::max(t.fencedMs, 1e-6);
    t.fenced = t.coverage < kMinTimestampCoverage;
    if (!t.fenced) renderer_->setStageTiming(Mode::Timestamps);
    return;
  }
  if (*renderer_->stageTiming() == Mode::Fenced) t.fenced = true;  // fenced by the renderer's settings
  if (t.fenced || oneOffFrame) return;
  if (++t.framesSeen == TimingCheck::kWarmupFrames || t.framesSeen % TimingCheck::kCheckEvery == 0) {
    renderer_->setStageTiming(Mode::Fenced);
    t.checking = true;
    t.framesChecked = 0;
    t.fencedMs = t.stampedMs = 0;
  }
}

void GiSystem::updateTechnique(const render::RenderSnapshot& snapshot) {
  auto t0 = std::chrono::steady_clock::now();
  technique_->update(TechniqueFrame{pending_, snapshot});
  pending_ = ChangeSet{};
  syncMs_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::string> GiSystem::debugViews() const {
  std::vector<std::string> views = {"final", "indirect"};
  for (const char* v : entry_->debugViews) views.push_back(v);
  return views;
}

bool GiSystem::setDebugView(std::string_view name) {
  const bool common = name == "final" || name == "indirect";
  if (!common && !technique_->setDebugView(name)) return false;
  if (common) technique_->setDebugView("final");
  indirectView_->enabled = name == "indirect";
  view_ = name;
  return true;
}

GiStats GiSystem::stats() const {
  GiStats s;
  s.bvh = bvh_ ? bvh_->stats() : BvhStats{};
  if (voxels_) s.voxels = voxels_->stats();
  s.syncMs = syncMs_;
  s.giMs = giMs_;
  if (budget_ && (timing_.fenced || timing_.coverage >= 0)) s.budgetTiming = timing_.fenced ? "fenced" : "timestamps";
  s.timestampCoverage = timing_.coverage;
  return s;
}

}  // namespace dyngi::gi
