// Every registered technique keeps the contract the GI system and the sample rely on (technique.h):
// the sections it declares are the ones the frame times, its options report what it uses, its debug
// views switch, and it reads the renderer's snapshot with every change since it last ran.
#include <gtest/gtest.h>

#include "render/gi_run.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
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
    GiRun run(context(), settingsFor(e), "cornell", 64, 64);
    run.step(3);
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
    bool hasVpls = false;
    for (const gi::OptionRef& r : run.gi->technique().options()) hasVpls |= std::string_view(r.spec->name) == "vpls";
    if (hasVpls) {
      EXPECT_EQ(run.gi->effectiveVplCount(), 100u);
    }
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
  GiRun run(context(), s, "cornell", 64, 64);
  run.update(), run.render();
  const ecs::Entity box = run.named("tall_box");
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
