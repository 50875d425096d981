// The renderer with the chosen GI, windowed or headless: device and window, the GI system and its
// features, the systems, the frame loop, and what the stats report.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>

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

GiSetup setUpGi(const Options& o, render::VulkanContext& ctx, render::Renderer& renderer, const ecs::World& world,
                const scene::AssetStore& assets) {
  GiSetup g;
  const bool voxelView = o.view == "voxels" || o.view == "svo-steps";
  const gi::VoxelDebugView voxelDebug = o.view == "voxels" ? gi::VoxelDebugView::Voxels : gi::VoxelDebugView::SvoSteps;
  if (o.usesGiSystem()) {
    if (world.count<scene::Light>() == 0)
      std::fprintf(stderr, "dyngi_sample: note: VPLs come from punctual lights only; this scene has none, so no indirect light\n");
    g.systemOwned = std::make_unique<gi::GiSystem>(ctx, assets, o.giSettings);
    g.system = g.systemOwned.get();
    // A value the technique adjusted (a VPL count rounded to a multiple of the bounces) is reported as used.
    gi::GiSettings asked = o.giSettings;
    for (const std::string& line : gi::adjustedOptions(g.system->techniqueEntry().options(asked), g.system->technique().options()))
      std::fprintf(stderr, "dyngi_sample: note: %s (the value the technique uses; --stats lists every value used)\n", line.c_str());
    g.system->attach(renderer);
    if (!voxelView) g.system->technique().setDebugView(o.view);  // parseOptions checked the name
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
    stats.scalars["vpls"] = gi->effectiveVplCount();  // as used (see the note above), not as asked
    gi::GiSettings asked = settings;
    for (const gi::OptionRef& r : gi->techniqueEntry().options(asked))
      if (std::string_view(r.spec->name) == "vpls") stats.scalars["vpls_requested"] = r.get();
    for (const gi::OptionRef& r : gi->technique().options()) {
      const std::string_view name = r.spec->name;
      if (name == "interleave" || name == "bounces") stats.scalars[std::string(name)] = r.get();
      if (name == "temporal") stats.scalars["temporal_sets"] = r.get();
      stats.sections["settings"][r.spec->name] = r.get();
    }
    gi::BudgetOptions budget = settings.budget;
    for (const gi::OptionRef& r : gi::bindOptions(budget)) stats.sections["settings"][r.spec->name] = r.get();
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
      stats.budget = out;
      if (!out.met)
        std::fprintf(stderr, "dyngi_sample: note: the GI budget of %g ms was not met: the GI costs more with every knob at its floor\n",
                     out.budgetMs);
    }
  }
  if (const gi::VoxelScene* voxels = g.voxels) {
    const gi::VoxelStats& v = voxels->stats();
    stats.scalars["voxel_resolution"] = settings.voxels.resolution;
    gi::VoxelSettings used = settings.voxels;
    for (const gi::OptionRef& r : gi::bindOptions(used)) stats.sections["settings"][r.spec->name] = r.get();
    stats.scalars["voxel_fragments"] = double(v.fragments);
    stats.scalars["svo_nodes"] = double(v.nodes);
    stats.scalars["svo_leaves"] = double(v.leaves);
    stats.scalars["svo_bytes"] = double(v.svoBytes);
    stats.scalars["voxel_total_bytes"] = double(v.totalBytes);
  }
}

}  // namespace

int runRealtime(const Options& o, ecs::World& world, scene::AssetStore& assets, RunStats& stats) {
  std::unique_ptr<platform::Window> window;
  if (!o.headless) {
    std::string why;
    window = platform::Window::create(o.width, o.height, "dyngi — " + o.scene, &why);
    if (!window) std::fprintf(stderr, "dyngi_sample: no window (%s); running headless\n", why.c_str());
  }
  const bool headless = !window;
  if (headless && o.gi == "path") {
    std::fprintf(stderr, "dyngi_sample: the path tracer's preview needs a window; path tracing headless\n");
    return runPathTracer(o, world, assets, stats);
  }
  std::optional<InputScript> script;
  if (!o.inputScript.empty()) {
    std::string error;
    script = InputScript::load(o.inputScript, &error);  // runApp checked it already
    if (!script) {
      std::fprintf(stderr, "dyngi_sample: %s\n", error.c_str());
      return 2;
    }
  }
  // A script runs to its last event (plus the frame that shows it) unless --frames says otherwise.
  const int frames = o.frames > 0 ? o.frames : script ? int(script->lastFrame()) + 2 : (headless ? kHeadlessDefaultFrames : -1);
  const bool fixedStep = headless || script;  // frame N is the same on every machine

  render::ContextOptions co;
#ifndef NDEBUG
  co.validation = true;  // debug builds always validate
#else
  co.validation = o.validation;
#endif
  co.requireValidation = o.validation;  // asked for on the command line: a missing layer is an error
  co.requireSwapchain = !headless;
  if (!headless) co.instanceExtensions = platform::Window::requiredInstanceExtensions();
  render::VulkanContext ctx(co);
  render::RendererSettings rs;
  rs.exposure = o.exposure;
  rs.stageTiming = o.stageTimes == "fenced" ? render::GpuTimer::Mode::Fenced : render::GpuTimer::Mode::Timestamps;
  render::Renderer renderer(ctx, rs);
  std::unique_ptr<render::Swapchain> swapchain;
  uint32_t width = o.width, height = o.height;
  if (!headless) {
    swapchain = std::make_unique<render::Swapchain>(ctx, window->createSurface(ctx.instance()));
    window->framebufferSize(width, height);
    if (width == 0 || height == 0) width = o.width, height = o.height;
    swapchain->recreate(width, height);
  }
  renderer.resize(width, height);

  GiSetup gi = setUpGi(o, ctx, renderer, world, assets);
  ecs::Scheduler scheduler;
  PlaySession session(o, ctx, renderer, scheduler, assets, gi.system, window.get(), std::move(script));
  if (window || session.scripted()) scheduler.add(ecs::Phase::Update, std::make_unique<FlyCameraSystem>(session.input(), session.uiHasMouse()));
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets));
  // --gi path in a window: the progressive path-traced preview, on a BVH that follows the world.
  std::unique_ptr<gi::EmbreeScene> previewBvh;
  std::unique_ptr<PathPreview> preview;
  if (o.gi == "path") {
    previewBvh = std::make_unique<gi::EmbreeScene>();
    preview = std::make_unique<PathPreview>(*previewBvh, assets, o.pathTracer);
    renderer.addFeature(preview.get());
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(*previewBvh, assets));
  }
  if (gi.systemOwned) scheduler.add(ecs::Phase::PostUpdate, std::move(gi.systemOwned));
  else if (gi.standaloneVoxels) scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(*gi.standaloneVoxels, assets));

  stats.device = ctx.deviceName();
  stats.stageTimes = o.stageTimes;
  stats.warmupFrames = o.warmupFrames();  // Mesa compiles pipelines on first use: keep them out of the medians
  MemoryLog memoryLog;
  if (!memoryLog.open(o.memoryLog)) return 1;
  ecs::FrameTime time;
  auto start = Clock::now(), last = start;
  int rendered = 0;
  double sceneTime = 0;      // scripted motion's clock in a window: stands still while paused (P)
  uint64_t pausedFrames = 0;  // the same with a fixed step
  for (uint64_t frame = 0; frames < 0 || rendered < frames; ++frame) {
    auto t0 = Clock::now();
    if (window) {
      window->pollEvents();
      if (window->shouldClose()) break;
      uint32_t fw, fh;
      window->framebufferSize(fw, fh);
      if (fw == 0 || fh == 0) {  // minimised: nothing to draw into
        window->waitEvents();
        last = Clock::now();
        continue;
      }
      if (fw != swapchain->extent().width || fh != swapchain->extent().height || !swapchain->valid()) {
        if (!swapchain->recreate(fw, fh)) continue;
        renderer.resize(fw, fh);
      }
    }
    time.dt = fixedStep ? 1.0 / 60.0 : std::chrono::duration<double>(t0 - last).count();
    // Fixed step: frame N's time is exactly (N - frames paused) / 60, as in every headless run before.
    time.time = fixedStep ? double(frame - pausedFrames) / 60.0 : sceneTime;
    if (session.paused()) ++pausedFrames;
    else sceneTime += time.dt;
    last = t0;
    time.frame = frame;
    session.beginFrame(frame, time.dt, world, assets, renderer.width(), renderer.height());
    scheduler.runFrame(world, time);
    auto tExtract = Clock::now();
    const render::RenderSnapshot snapshot = render::extractSnapshot(world, assets, frame);  // the frame's one snapshot
    double extractMs = std::chrono::duration<double, std::milli>(Clock::now() - tExtract).count();
    const render::FrameStats& fs = renderer.render(snapshot, swapchain.get());
    if (swapchain && !fs.presented) swapchain->recreate(renderer.width(), renderer.height());
    double frameMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    ++rendered;
    const bool keepGoing = session.endFrame(frame, snapshot, fs, frameMs);
    // The panel may have made a GI system, or rebuilt it (GiSystem::reset makes a new voxel scene).
    if (gi::GiSystem* made = session.gi().everMade()) {
      gi.system = made;
      gi.voxels = made->voxels();
    }
    memoryLog.frameRendered(rendered, ctx);
    if (rendered > stats.warmupFrames) {
      stats.frameMs.push(frameMs);
      std::map<std::string, double> perPass;  // a pass recorded more than once a frame (the temporal catch-up's gathers) counts once
      for (auto& [name, ms] : fs.gpuMs) perPass[name] += ms;
      for (auto& [name, ms] : perPass) stats.gpuStageMs[name].push(ms);
      for (auto& t : scheduler.lastTimings()) stats.cpuStageMs[t.name].push(t.cpuMs);
      stats.cpuStageMs["extract"].push(extractMs);
      stats.cpuStageMs["render_record"].push(fs.cpuRecordMs);
      stats.cpuStageMs["render_wait"].push(fs.cpuWaitMs);
      if (gi.system) {
        const gi::GiStats giStats = gi.system->stats();
        stats.cpuStageMs["gi_bvh_update"].push(giStats.bvh.updateMs);
        if (giStats.giMs >= 0) stats.giMs.push(giStats.giMs);
        for (const auto& [name, ms] : gi.system->technique().cpuMs()) stats.cpuStageMs[name].push(ms);
      }
    }
    if (!keepGoing) break;
  }
  stats.frames = rendered;
  if (window || session.scripted())
    stats.play = RunStats::Play{session.gi().mode(), entityLabel(world, session.play().selected), session.play().lastAction, session.scripted()};
  stats.width = renderer.width();
  stats.height = renderer.height();
  stats.scalars["draws"] = double(render::extractSnapshot(world, assets, 0).draws.size());
  stats.scalars["validation_errors"] = ctx.validationErrorCount();
  if (preview) stats.scalars["path_preview_spp"] = preview->samplesPerPixel();
  reportGi(session.gi().settings(), gi, stats);

  int status = session.status();
  if (rendered > 0)
    status |= writeImages(
        o, renderer.width(), renderer.height(), [&] { return renderer.readbackLdr(); }, [&] { return renderer.readback(render::TargetId::Hdr); });
  if (ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "dyngi_sample: %u Vulkan validation error(s)\n", ctx.validationErrorCount());
    status = 1;
  }
  return status;
}

}  // namespace dyngi::sample
