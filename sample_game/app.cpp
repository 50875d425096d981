#include "app.h"

#include <GLFW/glfw3.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <unistd.h>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/platform/window.h"
#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh_sync.h"
#include "dyngi/gi/path_tracer.h"
#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/job_pool.h"
#include "dyngi/gi/voxel_scene.h"
#include "scenes/builtin_scenes.h"
#include "stats.h"

namespace dyngi::sample {
namespace {

using Clock = std::chrono::steady_clock;

// WASD + right-mouse look on the active camera's Transform.
class FlyCameraSystem final : public ecs::System {
 public:
  explicit FlyCameraSystem(platform::Window& w) : window_(w) {}
  const char* name() const override { return "fly_camera"; }
  void run(ecs::World& world, const ecs::SystemContext& ctx) override {
    if (window_.keyDown(GLFW_KEY_ESCAPE)) window_.requestClose();
    ecs::Entity cam{};
    world.each<scene::ActiveCamera, scene::Transform>([&](ecs::Entity e, const scene::ActiveCamera&, const scene::Transform&) { cam = e; });
    if (cam.isNull()) return;
    const scene::Transform& t = world.get<scene::Transform>(cam);
    if (!initialised_) {
      glm::vec3 fwd = t.rotation * glm::vec3(0, 0, -1);
      yaw_ = std::atan2(-fwd.x, -fwd.z);
      pitch_ = std::asin(glm::clamp(fwd.y, -1.0f, 1.0f));
      initialised_ = true;
    }
    double dx, dy;
    window_.mouseDelta(dx, dy);
    bool look = window_.mouseButtonDown(GLFW_MOUSE_BUTTON_RIGHT);
    if (look) {
      yaw_ -= float(dx) * 0.003f;
      pitch_ = glm::clamp(pitch_ - float(dy) * 0.003f, -1.5f, 1.5f);
    }
    glm::quat rot = glm::angleAxis(yaw_, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch_, glm::vec3(1, 0, 0));
    glm::vec3 move(0.0f);
    if (window_.keyDown(GLFW_KEY_W)) move.z -= 1;
    if (window_.keyDown(GLFW_KEY_S)) move.z += 1;
    if (window_.keyDown(GLFW_KEY_A)) move.x -= 1;
    if (window_.keyDown(GLFW_KEY_D)) move.x += 1;
    if (window_.keyDown(GLFW_KEY_Q)) move.y -= 1;
    if (window_.keyDown(GLFW_KEY_E)) move.y += 1;
    if (move == glm::vec3(0.0f) && !look) return;  // untouched: no write, no change tick
    float speed = window_.keyDown(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.5f;
    scene::Transform& w = world.write<scene::Transform>(cam);
    w.rotation = rot;
    if (move != glm::vec3(0.0f)) w.translation += rot * glm::normalize(move) * speed * float(ctx.time.dt);
  }

 private:
  platform::Window& window_;
  float yaw_ = 0, pitch_ = 0;
  bool initialised_ = false;
};

constexpr int kMemoryLogEvery = 100;  // frames between two --memory-log lines

// Resident set size of this process, from /proc (0 where there is none).
uint64_t residentKiB() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long sizePages = 0, residentPages = 0;
  int n = std::fscanf(f, "%llu %llu", &sizePages, &residentPages);
  std::fclose(f);
  return n == 2 ? residentPages * uint64_t(sysconf(_SC_PAGESIZE)) / 1024 : 0;
}

bool writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) return false;
  f << text;
  return bool(f);
}

// --gi path: advance the scene `frames` frames (the BVH follows incrementally), then path-trace the
// last frame on the CPU. Needs no Vulkan device.
int runPathTracer(const Options& o, ecs::World& world, scene::AssetStore& assets, RunStats& stats) {
  gi::EmbreeScene bvh;
  ecs::Scheduler scheduler;
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets));
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::BvhSyncSystem>(bvh, assets));
  const int frames = o.frames > 0 ? o.frames : 1;
  ecs::FrameTime time;
  for (int f = 0; f < frames; ++f) {
    time.dt = 1.0 / 60.0;
    time.time = double(f) * time.dt;
    time.frame = uint64_t(f);
    scheduler.runFrame(world, time);
    for (auto& t : scheduler.lastTimings()) stats.cpuStageMs[t.name].push(t.cpuMs);
  }
  render::RenderSnapshot snapshot = render::extractSnapshot(world, assets, uint64_t(frames - 1));
  const gi::PathTracerSettings& pts = o.pathTracer;
  gi::PathTracerStats pstats;
  auto start = Clock::now();
  auto lastReport = start;
  auto progress = [&](uint32_t done, uint32_t total) {
    auto now = Clock::now();
    if (std::chrono::duration<double>(now - lastReport).count() < 2.0 && done != total) return;
    if (std::chrono::duration<double>(now - start).count() < 2.0) return;
    lastReport = now;
    std::fprintf(stderr, "path tracer: %u/%u spp (%.0f s)\n", done, total, std::chrono::duration<double>(now - start).count());
  };
  render::ImageRgba hdr = gi::pathTrace(snapshot, bvh, assets, o.width, o.height, pts, &pstats, progress);
  stats.frames = frames;
  stats.width = o.width;
  stats.height = o.height;
  stats.device = "cpu (" + std::to_string(gi::jobThreads()) + " threads)";
  stats.frameMs.push(pstats.ms);
  stats.gpuStageMs.clear();
  stats.cpuStageMs["path_trace"].push(pstats.ms);
  gi::PathTracerSettings used = pts;
  for (const gi::OptionRef& r : gi::bindOptions(used)) stats.sections["settings"][r.spec->name] = r.get();
  stats.scalars["spp"] = pts.spp;
  stats.scalars["bounces"] = pts.bounces;
  stats.scalars["msamples_per_second"] = pstats.samplesPerSecond * 1e-6;
  stats.scalars["bvh_instances"] = double(bvh.stats().instances);
  stats.scalars["draws"] = double(snapshot.draws.size());

  int status = 0;
  if (!o.out.empty()) {
    std::string err = render::writePng(o.out, o.width, o.height, render::tonemapToSrgb8(hdr, o.exposure, 0));
    if (!err.empty()) std::fprintf(stderr, "dyngi_sample: %s\n", err.c_str()), status = 1;
    else std::printf("wrote %s\n", o.out.c_str());
  }
  if (!o.hdrOut.empty()) {
    std::string err = render::writeExr(o.hdrOut, o.width, o.height, hdr);
    if (!err.empty()) std::fprintf(stderr, "dyngi_sample: %s\n", err.c_str()), status = 1;
    else std::printf("wrote %s\n", o.hdrOut.c_str());
  }
  return status;
}

}  // namespace

int runApp(const Options& o) {
  ecs::World world;
  scene::AssetStore assets;
  std::string sceneName = o.animate.empty() ? o.scene : "animate:" + o.animate;
  if (!o.animate.empty()) {
    std::string err = buildAnimatedScene(o.animate, world, assets, DYNGI_SHARED_SCENES_DEFAULT);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_sample: --animate %s: %s\n", o.animate.c_str(), err.c_str());
      return 2;
    }
  } else if (isBuiltinScene(o.scene)) {
    buildBuiltinScene(o.scene, world, assets);
  } else {
    scene::ImportReport report;
    scene::ImportOptions io;
    io.clip = o.clip;
    std::string err = scene::importGltf(o.scene, world, assets, &report, io);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_sample: %s\n", err.c_str());
      return 2;
    }
    if (report.missingClip) {
      std::string names;
      for (auto& c : report.clips) names += (names.empty() ? "" : ", ") + c;
      std::fprintf(stderr, "dyngi_sample: %s: no animation clip '%s' (available: %s)\n", o.scene.c_str(), o.clip.c_str(),
                   names.empty() ? "none" : names.c_str());
      return 2;
    }
    if (addDefaultLightIfUnlit(world))
      std::fprintf(stderr, "dyngi_sample: note: %s has no lights and no emissive surfaces; added a default directional light\n",
                   o.scene.c_str());
    else if (report.lights == 0)
      std::fprintf(stderr, "dyngi_sample: note: %s has no punctual lights; direct light comes from emissive surfaces only\n",
                   o.scene.c_str());
  }

  if (o.gi == "path") {
    if (!o.headless) std::fprintf(stderr, "dyngi_sample: the path tracer renders offscreen; running headless\n");
    RunStats stats;
    stats.scene = sceneName;
    stats.gi = o.gi;
    int status = runPathTracer(o, world, assets, stats);
    if (!o.stats.empty()) {
      if (!writeText(o.stats, stats.toJson())) std::fprintf(stderr, "dyngi_sample: %s: could not write stats\n", o.stats.c_str()), status = 1;
      else std::printf("wrote %s\n", o.stats.c_str());
    }
    std::printf("%s", stats.table().c_str());
    return status;
  }

  std::unique_ptr<platform::Window> window;
  if (!o.headless) {
    std::string why;
    window = platform::Window::create(o.width, o.height, "dyngi — " + o.scene, &why);
    if (!window) std::fprintf(stderr, "dyngi_sample: no window (%s); running headless\n", why.c_str());
  }
  const bool headless = !window;
  const int frames = o.frames > 0 ? o.frames : (headless ? kHeadlessDefaultFrames : -1);

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

  // GI: one ECS system plus its render features.
  const bool voxelView = o.view == "voxels" || o.view == "svo-steps";
  const gi::VoxelDebugView voxelDebug = o.view == "voxels" ? gi::VoxelDebugView::Voxels : gi::VoxelDebugView::SvoSteps;
  std::unique_ptr<gi::GiSystem> giOwned;
  gi::GiSystem* gi = nullptr;
  std::unique_ptr<gi::VoxelScene> standaloneVoxels;  // --view voxels without GI
  if (o.usesGiSystem()) {
    if (world.count<scene::Light>() == 0)
      std::fprintf(stderr, "dyngi_sample: note: VPLs come from punctual lights only; this scene has none, so no indirect light\n");
    giOwned = std::make_unique<gi::GiSystem>(ctx, assets, o.giSettings);
    gi = giOwned.get();
    // A value the technique adjusted (a VPL count rounded to a multiple of the bounces) is reported as used.
    gi::GiSettings asked = o.giSettings;
    for (const std::string& line : gi::adjustedOptions(gi->techniqueEntry().options(asked), gi->technique().options()))
      std::fprintf(stderr, "dyngi_sample: note: %s (the value the technique uses; --stats lists every value used)\n", line.c_str());
    gi->attach(renderer);
    if (!voxelView) gi->technique().setDebugView(o.view);  // parseOptions checked the name
  }
  gi::VoxelScene* voxels = gi ? gi->voxels() : nullptr;
  if (voxelView && voxels) voxels->setDebugView(voxelDebug);
  if (voxelView && !voxels) {
    gi::VoxelSettings vs = o.giSettings.voxels;
    vs.debugView = voxelDebug;
    standaloneVoxels = std::make_unique<gi::VoxelScene>(ctx, vs);
    renderer.addFeature(standaloneVoxels.get());
    voxels = standaloneVoxels.get();
  }

  ecs::Scheduler scheduler;
  if (window) scheduler.add(ecs::Phase::Update, std::make_unique<FlyCameraSystem>(*window));
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());
  scheduler.add(ecs::Phase::Update, std::make_unique<scene::AnimationSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::SkinningSystem>(assets));
  if (giOwned) scheduler.add(ecs::Phase::PostUpdate, std::move(giOwned));
  else if (standaloneVoxels) scheduler.add(ecs::Phase::PostUpdate, std::make_unique<gi::VoxelSyncSystem>(*standaloneVoxels, assets));

  RunStats stats;
  stats.scene = sceneName;
  stats.gi = o.gi;
  stats.device = ctx.deviceName();
  stats.warmupFrames = o.warmupFrames();  // Mesa compiles pipelines on first use: keep them out of the medians
  ecs::FrameTime time;
  auto start = Clock::now(), last = start;
  int rendered = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> memoryLog(nullptr, &std::fclose);
  if (!o.memoryLog.empty()) {
    memoryLog.reset(std::fopen(o.memoryLog.c_str(), "w"));
    if (!memoryLog) {
      std::fprintf(stderr, "dyngi_sample: %s: could not open the memory log\n", o.memoryLog.c_str());
      return 1;
    }
    std::fprintf(memoryLog.get(), "frame\trss_kib\tvk_allocations\tvk_device_bytes\n");
  }
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
      time.dt = std::chrono::duration<double>(t0 - last).count();
      time.time = std::chrono::duration<double>(t0 - start).count();
    } else {
      time.dt = 1.0 / 60.0;  // fixed step: frame N is the same on every machine
      time.time = double(frame) * time.dt;
    }
    last = t0;
    time.frame = frame;
    scheduler.runFrame(world, time);
    auto tExtract = Clock::now();
    render::RenderSnapshot snapshot = render::extractSnapshot(world, assets, frame);
    double extractMs = std::chrono::duration<double, std::milli>(Clock::now() - tExtract).count();
    const render::FrameStats& fs = renderer.render(snapshot, swapchain.get());
    if (swapchain && !fs.presented) swapchain->recreate(renderer.width(), renderer.height());
    double frameMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    ++rendered;
    if (memoryLog && rendered % kMemoryLogEvery == 0) {
      uint64_t deviceBytes = 0;
      for (uint32_t h = 0; h < VK_MAX_MEMORY_HEAPS; ++h) deviceBytes += ctx.heapBytesInUse(h);
      std::fprintf(memoryLog.get(), "%d\t%llu\t%llu\t%llu\n", rendered, (unsigned long long)residentKiB(),
                   (unsigned long long)ctx.liveAllocations(), (unsigned long long)deviceBytes);
      std::fflush(memoryLog.get());
    }
    if (rendered > stats.warmupFrames) {
      stats.frameMs.push(frameMs);
      for (auto& [name, ms] : fs.gpuMs) stats.gpuStageMs[name].push(ms);
      for (auto& t : scheduler.lastTimings()) stats.cpuStageMs[t.name].push(t.cpuMs);
      stats.cpuStageMs["extract"].push(extractMs);
      stats.cpuStageMs["render_record"].push(fs.cpuRecordMs);
      stats.cpuStageMs["render_wait"].push(fs.cpuWaitMs);
      if (gi) {
        stats.cpuStageMs["gi_bvh_update"].push(gi->stats().bvh.updateMs);
        for (const auto& [name, ms] : gi->technique().cpuMs()) stats.cpuStageMs[name].push(ms);
      }
    }
  }
  stats.frames = rendered;
  stats.width = renderer.width();
  stats.height = renderer.height();
  stats.scalars["draws"] = double(render::extractSnapshot(world, assets, 0).draws.size());
  stats.scalars["validation_errors"] = ctx.validationErrorCount();
  if (gi) {
    stats.scalars["vpls"] = gi->effectiveVplCount();  // as used (see the note above), not as asked
    gi::GiSettings asked = o.giSettings;
    for (const gi::OptionRef& r : gi->techniqueEntry().options(asked))
      if (std::string_view(r.spec->name) == "vpls") stats.scalars["vpls_requested"] = r.get();
    for (const gi::OptionRef& r : gi->technique().options()) {
      const std::string_view name = r.spec->name;
      if (name == "interleave" || name == "bounces") stats.scalars[std::string(name)] = r.get();
      if (name == "temporal") stats.scalars["temporal_sets"] = r.get();
      stats.sections["settings"][r.spec->name] = r.get();
    }
    for (auto& [section, values] : gi->technique().statsSections())
      for (auto& [key, value] : values) stats.sections[section][key] = value;
  }
  if (voxels) {
    const gi::VoxelStats& v = voxels->stats();
    stats.scalars["voxel_resolution"] = o.giSettings.voxels.resolution;
    gi::VoxelSettings used = o.giSettings.voxels;
    for (const gi::OptionRef& r : gi::bindOptions(used)) stats.sections["settings"][r.spec->name] = r.get();
    stats.scalars["voxel_fragments"] = double(v.fragments);
    stats.scalars["svo_nodes"] = double(v.nodes);
    stats.scalars["svo_leaves"] = double(v.leaves);
    stats.scalars["svo_bytes"] = double(v.svoBytes);
    stats.scalars["voxel_total_bytes"] = double(v.totalBytes);
  }

  int status = 0;
  if (rendered > 0 && !o.out.empty()) {
    std::string err = render::writePng(o.out, renderer.width(), renderer.height(), renderer.readbackLdr());
    if (!err.empty()) std::fprintf(stderr, "dyngi_sample: %s\n", err.c_str()), status = 1;
    else std::printf("wrote %s\n", o.out.c_str());
  }
  if (rendered > 0 && !o.hdrOut.empty()) {
    std::string err = render::writeExr(o.hdrOut, renderer.width(), renderer.height(), renderer.readback(render::TargetId::Hdr));
    if (!err.empty()) std::fprintf(stderr, "dyngi_sample: %s\n", err.c_str()), status = 1;
    else std::printf("wrote %s\n", o.hdrOut.c_str());
  }
  if (!o.stats.empty()) {
    if (!writeText(o.stats, stats.toJson())) std::fprintf(stderr, "dyngi_sample: %s: could not write stats\n", o.stats.c_str()), status = 1;
    else std::printf("wrote %s\n", o.stats.c_str());
  }
  std::printf("%s", stats.table().c_str());
  if (ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "dyngi_sample: %u Vulkan validation error(s)\n", ctx.validationErrorCount());
    status = 1;
  }
  return status;
}

}  // namespace dyngi::sample
