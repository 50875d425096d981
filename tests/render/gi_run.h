#pragma once
// A GI system on a built-in scene with its own renderer, stepped with a fixed time step: the render
// tests' way to run a technique for some frames and read back what it drew.
#include <functional>
#include <memory>
#include <set>
#include <string>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/scene/components.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/path_tracer.h"
#include "render/cornell_regions.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

namespace dyngi::test {

struct GiRun {
  ecs::World world;
  scene::AssetStore assets;
  ecs::Scheduler scheduler;
  gi::GiSystem* gi = nullptr;
  std::unique_ptr<render::Renderer> renderer;
  uint64_t frame = 0;               // frames the systems ran
  std::set<std::string> gpuSections;  // every section the renderer timed so far

  GiRun(render::VulkanContext& ctx, const gi::GiSettings& s, const std::string& sceneName = "cornell", uint32_t width = 128,
        uint32_t height = 128)
      : GiRun(ctx, s, [&](ecs::World& w, scene::AssetStore& a) { sample::buildBuiltinScene(sceneName, w, a); }, width, height) {}
  // A scene the test builds itself (with a camera).
  GiRun(render::VulkanContext& ctx, const gi::GiSettings& s, const std::function<void(ecs::World&, scene::AssetStore&)>& build,
        uint32_t width, uint32_t height) {
    build(world, assets);
    renderer = std::make_unique<render::Renderer>(ctx);
    renderer->resize(width, height);
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
    auto g = std::make_unique<gi::GiSystem>(ctx, assets, s);
    gi = g.get();
    gi->attach(*renderer);
    scheduler.add(ecs::Phase::PostUpdate, std::move(g));
  }
  // A frame: the systems, then the renderer. update() and render() apart let a test run the ECS more
  // often than it renders.
  void step(int n = 1) {
    for (int i = 0; i < n; ++i) update(), render();
  }
  void update() { scheduler.runFrame(world, ecs::FrameTime{1.0 / 60, double(frame) / 60, frame}), ++frame; }
  void render() {
    const render::FrameStats& fs = renderer->render(render::extractSnapshot(world, assets, frame - 1));
    for (const auto& [name, ms] : fs.gpuMs) gpuSections.insert(name);
  }
  render::ImageRgba hdr() { return renderer->readback(render::TargetId::Hdr); }
  // The last frame with its G-buffer and snapshot, for per-region comparisons (cornellRegions).
  Frame readFrame() {
    Frame f;
    f.width = renderer->width();
    f.height = renderer->height();
    f.hdr = hdr();
    f.position = renderer->readback(render::TargetId::Position);
    f.normal = renderer->readback(render::TargetId::Normal);
    f.snapshot = render::extractSnapshot(world, assets, frame);
    return f;
  }
  // The reference path tracer on the world as it is now, at the G-buffer's sample positions.
  render::ImageRgba pathTraced(uint32_t spp, uint32_t bounces) {
    gi::EmbreeScene bvh;
    bvh.sync(world, assets, 0);
    gi::PathTracerSettings pts;
    pts.spp = spp;
    pts.bounces = bounces;
    pts.pixelJitter = false;
    return gi::pathTrace(render::extractSnapshot(world, assets, frame), bvh, assets, renderer->width(), renderer->height(), pts);
  }
  render::ImageRgba indirect() { return renderer->readback(render::TargetId::Indirect); }
  ecs::Entity named(const std::string& n) {
    ecs::Entity found{};
    world.each<scene::Name>([&](ecs::Entity e, const scene::Name& nm) { if (nm.value == n) found = e; });
    return found;
  }
};

}  // namespace dyngi::test
