#include <chrono>
#include <cstdio>

#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/render/snapshot.h"
#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/bvh_sync.h"
#include "dyngi/gi/job_pool.h"
#include "dyngi/gi/path_tracer.h"
#include "outputs.h"
#include "runs.h"

namespace dyngi::sample {

using Clock = std::chrono::steady_clock;

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
  addSettings(stats, gi::bindOptions(used));
  stats.scalars["spp"] = pts.spp;
  stats.scalars["bounces"] = pts.bounces;
  stats.scalars["msamples_per_second"] = pstats.samplesPerSecond * 1e-6;
  stats.scalars["bvh_instances"] = double(bvh.stats().instances);
  stats.scalars["draws"] = double(snapshot.draws.size());

  return writeImages(
      o, o.width, o.height, [&] { return render::tonemapToSrgb8(hdr, o.exposure, 0); }, [&] { return hdr; });
}

}  // namespace dyngi::sample
