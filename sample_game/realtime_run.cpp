// The renderer with the chosen GI, windowed or headless: device and window, the GI system and its
// features, the systems, the frame loop, and what the stats report.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "dyngi/engine/platform/files.h"
#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/platform/window.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/render/swapchain.h"
#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh_sync.h"
#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/voxel_scene.h"
#include "fly_camera.h"
#include "outputs.h"
#include "play/path_preview.h"
#include "play/play_session.h"
#include "runs.h"

namespace dyngi::sample {
namespace {

using Clock = std::chrono::steady_clock;

// The GI of the run: the GI system with its technique, or for --view voxels|svo-steps without GI a
// voxel scene of its own. Owned here until the scheduler takes the system.
struct GiSetup {
  std::unique_ptr<gi::GiSystem> systemOwned;
  gi::GiSystem* system = nullptr;
  std::unique_ptr<gi::VoxelScene> standaloneVoxels;
  gi::VoxelScene* voxels = nullptr;  // the one the voxel views and stats read, if any
};

GiSetup setUpGi(const Options& o, render::VulkanContext& ctx, render::Renderer& renderer, const scene::AssetStore& assets) {
  GiSetup g;
  const bool voxelView = o.view == "voxels" || o.view == "svo-steps";
  const gi::VoxelDebugView voxelDebug = o.view == "voxels" ? gi::VoxelDebugView::Voxels : gi::VoxelDebugView::SvoSteps;
  if (o.usesGiSystem()) {
    g.systemOwned = std::make_unique<gi::GiSystem>(ctx, assets, o.giSettings);
    g.system = g.systemOwned.get();
    // A value the technique adjusted (a VPL count rounded to a multiple of the bounces) is reported as used.
    gi::GiSettings asked = o.giSettings;
    for (const std::string& line : gi::adjustedOptions(g.system->techniqueEntry().options(asked), g.system->technique().options()))
      std::fprintf(stderr, "dyngi_sample: note: %s (the value the technique uses; --stats lists every value used)\n", line.c_str());
    g.system->attach(renderer);
    if (!voxelView) g.system->setDebugView(o.view);  // parseOptions checked the name
    g.voxels = g.system->voxels();
  }
  if (voxelView && g.voxels) g.voxels->setDebugView(voxelDebug);
  if (voxelView && !g.voxels) {
    gi::VoxelSettings vs = o.giSettings.voxels;
    vs.debugView = voxelDebug;
    g.standaloneVoxels = std::make_unique<gi::VoxelScene>(ctx, vs);
    renderer.addFeature(g.standaloneVoxels.get());
    g.voxels = g.standaloneVoxels.get();
  }
  return g;
}

// The GI's settings as used and its figures, once at the end of the run.
// `settings`: the GI's settings at the end of the run (the panel may have changed them).
void reportGi(const gi::GiSettings& settings, const GiSetup& g, RunStats& stats) {
  if (gi::GiSystem* gi = g.system) {
    gi::GiSettings asked = settings;
    if (auto r = gi::findOption(gi->techniqueEntry().options(asked), "vpls")) stats.scalars["vpls_requested"] = r->get();
    // The technique's options as it uses them (a VPL count rounded to a multiple of the bounces): the
    // counts take the key with dashes as underscores.
    const std::vector<gi::OptionRef> used = gi->technique().options();
    for (const char* count : {"vpls", "interleave", "bounces", "temporal-sets"})
      if (auto r = gi::findOption(used, count)) stats.scalars[count == std::string("temporal-sets") ? "temporal_sets" : count] = r->get();
    addSettings(stats, used);
    gi::BudgetOptions budget = settings.budget;
    addSettings(stats, gi::bindOptions(budget));
    for (auto& [section, values] : gi->technique().statsSections())
      for (auto& [key, value] : values) stats.sections[section][key] = value;
    if (const gi::BudgetController* b = gi->budget()) {
      RunStats::Budget out;
      out.budgetMs = b->budgetMs();
      out.met = b->budgetMet();
      out.level = b->level();
      out.floorLevel = b->floorLevel();
      out.knobs = b->knobValues();
      for (const gi::BudgetController::Change& c : b->changes()) out.trace.push_back({c.frame, c.level, c.medianMs, b->valuesAt(c.level)});
      const gi::GiStats gs = gi->stats();
      out.timing = gs.budgetTiming;
      out.timestampCoverage = gs.timestampCoverage;
      stats.budget = out;
      if (out.timing == "fenced" && stats.stageTimes != "fenced") stats.stageTimes = "timestamps, then fenced (the GI budget's timing check)";
      if (!out.met)
        std::fprintf(stderr, "dyngi_sample: note: the GI budget of %g ms was not met: the GI costs more with every knob at its floor\n",
                     out.budgetMs);
    }
  }
  if (const gi::VoxelScene* voxels = g.voxels) {
    const gi::VoxelStats& v = voxels->stats();
    stats.scalars["voxel_resolution"] = settings.voxels.resolution;
    stats.scalars["voxel_size_m"] = double(voxels->volume().voxelSize);  // a room's 1.6 cm; a wide world's volume follows the camera
    stats.scalars["voxel_windowed"] = v.windowed ? 1.0 : 0.0;
    stats.scalars["voxel_volume_moves"] = double(v.volumeMoves);
    gi::VoxelSettings used = settings.voxels;
    addSettings(stats, gi::bindOptions(used));
    stats.scalars["voxel_fragments"] = double(v.fragments);
    stats.scalars["voxel_entities_deferred"] = double(v.entitiesDeferred);  // by a GI budget's voxelization cap, last frame
    stats.scalars["voxel_draws_by_compute"] = double(v.drawsComputeVoxelized);  // of small triangles, at the last voxelization
    stats.scalars["svo_nodes"] = double(v.nodes);
    stats.scalars["svo_leaves"] = double(v.leaves);
    stats.scalars["svo_bytes"] = double(v.svoBytes);
    stats.scalars["voxel_total_bytes"] = double(v.totalBytes);
  }
}

// What the window says about this frame.
enum class WindowStep { Draw, Minimised, NotReady, Close };

WindowStep pumpWindow(platform::Window& window, render::Swapchain& swapchain, render::Renderer& renderer) {
  window.pollEvents();
  if (window.shouldClose()) return WindowStep::Close;
  uint32_t fw, fh;
  window.framebufferSize(fw, fh);
  if (fw == 0 || fh == 0) {  // minimised: nothing to draw into
    window.waitEvents();
    return WindowStep::Minimised;
  }
  if (fw != swapchain.extent().width || fh != swapchain.extent().height || !swapchain.valid()) {
    if (!swapchain.recreate(fw, fh)) return WindowStep::NotReady;
    renderer.resize(fw, fh);
  }
  return WindowStep::Draw;
}

render::ContextOptions contextOptions(const Options& o, bool headless) {
  render::ContextOptions co;
#ifndef NDEBUG
  co.validation = true;  // debug builds always validate
#else
  co.validation = o.validation;
#endif
  co.requireValidation = o.validation;  // asked for on the command line: a missing layer is an error
  co.requireSwapchain = !headless;
  if (!headless) co.instanceExtensions = platform::Window::requiredInstanceExtensions();
  return co;
}

// One rendered frame's timings into the run's series (after the warm-up).
void recordFrameTimes(RunStats& stats, const render::FrameStats& fs, double frameMs, double extractMs, const ecs::Scheduler& scheduler,
                      gi::GiSystem* gi) {
  stats.frameMs.push(frameMs);
  std::map<std::string, double> perPass;  // a pass recorded more than once a frame (the temporal catch-up's gathers) counts once
  for (auto& [name, ms] : fs.gpuMs) perPass[name] += ms;
  for (auto& [name, ms] : perPass) stats.gpuStageMs[name].push(ms);
  for (auto& t : scheduler.lastTimings()) stats.cpuStageMs[t.name].push(t.cpuMs);
  stats.cpuStageMs["extract"].push(extractMs);
  stats.cpuStageMs["render_record"].push(fs.cpuRecordMs);
  stats.cpuStageMs["render_wait"].push(fs.cpuWaitMs);
  if (!gi) return;
  const gi::GiStats giStats = gi->stats();
  stats.cpuStageMs["gi_bvh_update"].push(giStats.bvh.updateMs);
  if (giStats.giMs >= 0) stats.giMs.push(giStats.giMs);
  for (const auto& [name, ms] : gi->technique().cpuMs()) stats.cpuStageMs[name].push(ms);
}

// A run's device, window, renderer, GI and systems, and its frame loop.
class RealtimeRun {
 public:
  RealtimeRun(const Options& o, ecs::World& world, scene::AssetStore& assets, std::unique_ptr<platform::Window> window,
              std::optional<InputScript> script)
      : o_(o), world_(world), assets_(assets), window_(std::move(window)), ctx_(contextOptions(o, !window_)), renderer_(ctx_, rendererSettings(o)) {
    uint32_t width = o.width, height = o.height;
    if (window_) {
      swapchain_ = std::make_unique<render::Swapchain>(ctx_, window_->createSurface(ctx_.instance()));
      window_->framebufferSize(width, height);
      if (width == 0 || height == 0) width = o.width, height = o.height;
      swapchain_->recreate(width, height);
    }
    renderer_.resize(width, height);
    gi_ = setUpGi(o, ctx_, renderer_, assets);
    session_ = std::make_unique<PlaySession>(o, ctx_, renderer_, scheduler_, assets, gi_.system, window_.get(), std::move(script));
    addSystems();
  }

  // Renders `frames` frames (-1: until the window closes or the script ends); returns the exit status.
  int run(int frames, RunStats& stats) {
    stats.device = ctx_.deviceName();
    stats.stageTimes = o_.stageTimes;
    stats.warmupFrames = o_.warmupFrames();  // Mesa compiles pipelines on first use: keep them out of the medians
    MemoryLog memoryLog;
    if (!memoryLog.open(o_.memoryLog)) return 1;
    const bool fixedStep = !window_ || session_->scripted();  // frame N is the same on every machine
    last_ = Clock::now();
    int rendered = 0;
    for (uint64_t frame = 0; frames < 0 || rendered < frames; ++frame) {
      auto t0 = Clock::now();
      if (window_) {
        const WindowStep step = pumpWindow(*window_, *swapchain_, renderer_);
        if (step == WindowStep::Close) break;
        if (step == WindowStep::Minimised) last_ = Clock::now();
        if (step != WindowStep::Draw) continue;
      }
      advanceTime(frame, fixedStep, t0);
      const bool keepGoing = renderFrame(frame, t0, ++rendered, stats);
      memoryLog.frameRendered(rendered, ctx_);
      if (!keepGoing) break;
    }
    return finish(rendered, stats) | memoryLog.close();
  }

 private:
  static render::RendererSettings rendererSettings(const Options& o) {
    render::RendererSettings rs;
    rs.exposure = o.exposure;
    rs.stageTiming = o.stageTimes == "fenced" ? render::GpuTimer::Mode::Fenced : render::GpuTimer::Mode::Timestamps;
    return rs;
  }

  void addSystems() {
    if (window_ || session_->scripted())
      scheduler_.add(ecs::Phase::Update, std::make_unique<FlyCameraSystem>(session_->input(), session_->uiHasMouse()));
    scheduler_.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());
    scheduler_.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
    scheduler_.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
    scheduler_.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets_));
    // --gi path in a window: the progressive path-traced preview, on a BVH that follows the world.
    if (o_.gi == "path") {
      previewBvh_ = std::make_unique<gi::EmbreeScene>();
      preview_ = std::make_unique<PathPreview>(*previewBvh_, assets_, o_.pathTracer);
      renderer_.addFeature(preview_.get());
      scheduler_.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(*previewBvh_, assets_));
    }
    if (gi_.systemOwned) scheduler_.add(ecs::Phase::PostUpdate, std::move(gi_.systemOwned));
    else if (gi_.standaloneVoxels) scheduler_.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(*gi_.standaloneVoxels, assets_));
  }

  // The scene's clock: with a fixed step frame N's time is exactly (N - frames paused) / 60; in a window
  // it stands still while paused (P).
  void advanceTime(uint64_t frame, bool fixedStep, Clock::time_point t0) {
    time_.dt = fixedStep ? 1.0 / 60.0 : std::chrono::duration<double>(t0 - last_).count();
    time_.time = fixedStep ? double(frame - pausedFrames_) / 60.0 : sceneTime_;
    if (session_->paused()) ++pausedFrames_;
    else sceneTime_ += time_.dt;
    last_ = t0;
    time_.frame = frame;
  }

  bool renderFrame(uint64_t frame, Clock::time_point t0, int rendered, RunStats& stats) {
    session_->beginFrame(frame, time_.dt, world_, assets_, renderer_.width(), renderer_.height());
    scheduler_.runFrame(world_, time_);
    auto tExtract = Clock::now();
    render::extractSnapshot(world_, assets_, frame, snapshot_);  // the frame's one snapshot, in last frame's memory
    const render::RenderSnapshot& snapshot = snapshot_;
    const double extractMs = std::chrono::duration<double, std::milli>(Clock::now() - tExtract).count();
    const render::FrameStats& fs = renderer_.render(snapshot, swapchain_.get());
    if (swapchain_ && !fs.presented) swapchain_->recreate(renderer_.width(), renderer_.height());
    const double frameMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const bool keepGoing = session_->endFrame(frame, snapshot, fs, frameMs);
    // The panel may have made a GI system, or rebuilt it (GiSystem::reset makes a new voxel scene).
    if (gi::GiSystem* made = session_->gi().everMade()) {
      gi_.system = made;
      gi_.voxels = made->voxels();
    }
    if (rendered > stats.warmupFrames) recordFrameTimes(stats, fs, frameMs, extractMs, scheduler_, gi_.system);
    return keepGoing;
  }

  int finish(int rendered, RunStats& stats) {
    stats.frames = rendered;
    if (window_ || session_->scripted())
      stats.play = RunStats::Play{session_->gi().mode(), entityLabel(world_, session_->play().selected), session_->play().lastAction,
                                  session_->scripted()};
    stats.width = renderer_.width();
    stats.height = renderer_.height();
    stats.scalars["draws"] = double(snapshot_.draws.size());  // the last frame's
    stats.scalars["validation_errors"] = ctx_.validationErrorCount();
    addMemory(stats, ctx_);
    if (preview_) stats.scalars["path_preview_spp"] = preview_->samplesPerPixel();
    reportGi(session_->gi().settings(), gi_, stats);
    int status = session_->status();
    if (rendered > 0)
      status |= writeImages(
          o_, renderer_.width(), renderer_.height(), [&] { return renderer_.readbackLdr(); }, [&] { return renderer_.readback(render::TargetId::Hdr); });
    if (ctx_.validationErrorCount() > 0) {
      std::fprintf(stderr, "dyngi_sample: %u Vulkan validation error(s)\n", ctx_.validationErrorCount());
      status = 1;
    }
    return status;
  }

  const Options& o_;
  ecs::World& world_;
  scene::AssetStore& assets_;
  std::unique_ptr<platform::Window> window_;
  render::VulkanContext ctx_;
  render::Renderer renderer_;
  render::RenderSnapshot snapshot_;  // this frame's, reusing last frame's memory
  std::unique_ptr<render::Swapchain> swapchain_;
  GiSetup gi_;
  ecs::Scheduler scheduler_;
  std::unique_ptr<PlaySession> session_;
  std::unique_ptr<gi::EmbreeScene> previewBvh_;
  std::unique_ptr<PathPreview> preview_;
  ecs::FrameTime time_;
  Clock::time_point last_;
  double sceneTime_ = 0;      // scripted motion's clock in a window
  uint64_t pausedFrames_ = 0;  // the same with a fixed step
};

}  // namespace

int runRealtime(const Options& o, ecs::World& world, scene::AssetStore& assets, RunStats& stats) {
  std::unique_ptr<platform::Window> window;
  if (!o.headless) {
    std::string why;
    window = platform::Window::create(o.width, o.height, "dyngi — " + o.scene, &why);
    if (!window) std::fprintf(stderr, "dyngi_sample: no window (%s); running headless\n", why.c_str());
  }
  if (!window && o.gi == "path") {
    std::fprintf(stderr, "dyngi_sample: the path tracer's preview needs a window; path tracing headless\n");
    return runPathTracer(o, world, assets, stats);
  }
  std::optional<InputScript> script;
  if (!o.inputScript.empty()) {
    std::string error;
    script = InputScript::load(o.inputScript, &error);  // runApp checked it already
    if (!script) {
      std::fprintf(stderr, "dyngi_sample: %s\n", dyngi::platform::oneLine(error, 1000).c_str());
      return 2;
    }
  }
  // A script runs to its last event (plus the frame that shows it) unless --frames says otherwise.
  const int frames = o.frames > 0 ? o.frames : script ? int(script->lastFrame()) + 2 : (window ? -1 : kHeadlessDefaultFrames);
  RealtimeRun run(o, world, assets, std::move(window), std::move(script));
  return run.run(frames, stats);
}

}  // namespace dyngi::sample
