// Every registered technique keeps the contract the GI system and the sample rely on (technique.h):
// the sections it declares are the ones the frame times, its options report what it uses, its debug
// views switch, and it reads the renderer's snapshot with every change since it last ran.
#include <gtest/gtest.h>

#include <set>

#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/gi_system.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 64;

struct GiFrames {
  ecs::World world;
  scene::AssetStore assets;
  ecs::Scheduler scheduler;
  gi::GiSystem* gi = nullptr;
  std::unique_ptr<render::Renderer> renderer;
  uint64_t frame = 0;
  std::set<std::string> gpuSections;

  GiFrames(render::VulkanContext& ctx, const gi::GiSettings& s) {
    sample::buildBuiltinScene("cornell", world, assets);
    renderer = std::make_unique<render::Renderer>(ctx);
    renderer->resize(kSize, kSize);
    scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
    auto g = std::make_unique<gi::GiSystem>(ctx, assets, s);
    gi = g.get();
    gi->attach(*renderer);
    scheduler.add(ecs::Phase::PostUpdate, std::move(g));
  }
  void update() { scheduler.runFrame(world, ecs::FrameTime{1.0 / 60, double(frame) / 60, frame}), ++frame; }
  void render() {
    const render::FrameStats& fs = renderer->render(render::extractSnapshot(world, assets, frame));
    for (auto& [name, ms] : fs.gpuMs) gpuSections.insert(name);
  }
};

gi::GiSettings settingsFor(const gi::TechniqueEntry& e) {
  gi::GiSettings s;
  s.technique = e.name;
  // Two bounces and an odd count, so every section runs and the count must be rounded.
  for (const gi::OptionRef& r : e.options(s)) {
    if (std::string_view(r.spec->name) == "bounces") r.set(2);
    if (std::string_view(r.spec->name) == "vpls") r.set(101);
  }
  return s;
}
}  // namespace

TEST_F(RenderTest, EveryTechniqueTimesTheSectionsItDeclaresAndReportsTheOptionsItUses) {
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    SCOPED_TRACE(e.name);
    GiFrames run(context(), settingsFor(e));
    for (int i = 0; i < 3; ++i) run.update(), run.render();
    for (const char* section : run.gi->technique().timedSections())
      EXPECT_TRUE(run.gpuSections.count(section)) << "declared but never timed: " << section;
    for (const gi::OptionRef& r : run.gi->technique().options()) {
      if (std::string_view(r.spec->name) == "vpls") {
        EXPECT_EQ(r.get(), 100.0) << "101 over 2 bounces is used as 100";
      }
      if (std::string_view(r.spec->name) == "bounces") {
        EXPECT_EQ(r.get(), 2.0);
      }
    }
    EXPECT_EQ(run.gi->effectiveVplCount(), 100u);
    for (const char* view : e.debugViews) EXPECT_TRUE(run.gi->technique().setDebugView(view)) << view;
    EXPECT_TRUE(run.gi->technique().setDebugView("final") || e.debugViews.empty());
    EXPECT_FALSE(run.gi->technique().setDebugView("no-such-view"));
  }
  EXPECT_THROW(gi::GiSystem(context(), scene::AssetStore{}, gi::GiSettings{.technique = "no-such-technique"}), std::invalid_argument);
}

// The ECS may run more often than the renderer draws: the VPLs on a wall that moved in a frame that was
// never rendered are invalidated all the same, at the next rendered frame (the change sets merge).
TEST_F(RenderTest, ChangesFromFramesThatWereNotRenderedReachTheTechnique) {
  gi::GiSettings s;
  s.technique = "temporal";
  s.temporal.vpl.vplCount = 256;
  s.temporal.reshootBudget = 256;
  s.temporal.temporalSets = 1;
  GiFrames run(context(), s);
  run.update(), run.render();
  ecs::Entity box{};
  run.world.each<scene::Name>([&](ecs::Entity e, const scene::Name& n) {
    if (n.value == "tall_box") box = e;
  });
  ASSERT_FALSE(box.isNull());
  uint32_t onBox = 0;
  for (const gi::PathVpl& v : run.gi->paths()->vpls()) onBox += v.valid && v.surface == box;
  ASSERT_GT(onBox, 0u) << "the light reaches the box";
  const uint64_t invalidatedBefore = run.gi->paths()->stats().invalidatedTotal;
  run.world.template write<scene::Transform>(box).translation.x += 0.05f;
  run.update();  // the move, not rendered
  run.update();  // a frame with no change
  run.render();
  EXPECT_GE(run.gi->paths()->stats().invalidatedTotal - invalidatedBefore, onBox) << "every VPL on the moved box";
}
