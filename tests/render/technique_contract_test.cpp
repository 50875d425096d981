// Every registered technique keeps the contract the GI system and the sample rely on (technique.h):
// the sections it declares are the ones the frame times, its options report what it uses, its debug
// views switch, and it reads the renderer's snapshot with every change since it last ran.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "testing/gi_probes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
gi::GiSettings settingsFor(const gi::TechniqueEntry& e) {
  gi::GiSettings s;
  s.technique = e.name;
  // Two bounces and an odd count, so every section runs and the count must be rounded.
  for (const gi::OptionRef& r : e.options(s)) {
    if (r.spec->name == "bounces") r.set(2);
    if (r.spec->name == "vpls") r.set(101);
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
      if (r.spec->name == "vpls") {
        EXPECT_EQ(r.get(), 100.0) << "101 over 2 bounces is used as 100";
      }
      if (r.spec->name == "bounces") {
        EXPECT_EQ(r.get(), 2.0);
      }
    }
    EXPECT_FALSE(run.gi->setDebugView("no-such-view"));
  }
  // On a smaller screen the VPL techniques also time the reduction and the upsample, and count them.
  for (const char* technique : {"temporal", "many-lights"}) {
    SCOPED_TRACE(technique);
    gi::GiSettings s = settingsFor(*gi::findTechnique(technique));
    s.temporal.vpl.gatherScale = s.manyLights.vpl.gatherScale = 2.0f;
    GiRun run(context(), s, "cornell", 64, 64);
    run.step(3);
    const std::vector<const char*> sections = run.gi->technique().timedSections();
    for (std::string_view name : {"reduce", "upsample"}) {
      EXPECT_TRUE(run.gpuSections.count(std::string(name))) << name;
      EXPECT_NE(std::find(sections.begin(), sections.end(), name), sections.end()) << name;
    }
  }
  EXPECT_THROW(gi::GiSystem(context(), scene::AssetStore{}, gi::GiSettings{.technique = "no-such-technique"}), std::invalid_argument);
}

// Every technique has the views "final" and "indirect" plus its own. Each is drawn over the same frame
// as a run showing "final" (the runs are deterministic): "final" is that image bit for bit, every other
// view differs from it, and "indirect" is exactly the GI's indirect diffuse output (E / pi before
// albedo) that the lighting reads.
TEST_F(RenderTest, EveryTechniqueDrawsEachOfItsViews) {
  constexpr int kFrames = 3;
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    SCOPED_TRACE(e.name);
    GiRun reference(context(), settingsFor(e), "cornell", 48, 48);
    reference.step(kFrames);
    const render::ImageRgba final = reference.hdr();
    const std::vector<std::string> views = reference.gi->debugViews();
    ASSERT_GE(views.size(), 2u);
    EXPECT_EQ(views[0], "final");
    EXPECT_EQ(views[1], "indirect");
    EXPECT_EQ(views.size(), e.debugViews.size() + 2);
    EXPECT_FALSE(reference.gi->setDebugView("no-such-view"));
    for (const std::string& view : views) {
      SCOPED_TRACE(view);
      GiRun run(context(), settingsFor(e), "cornell", 48, 48);
      ASSERT_TRUE(run.gi->setDebugView(view));
      run.step(kFrames);
      const render::ImageRgba shown = run.hdr();
      double differs = 0;
      for (size_t i = 0; i < shown.size(); ++i)
        for (int c = 0; c < 4; ++c) differs += std::abs(shown[i][c] - final[i][c]);
      if (view == "final") EXPECT_EQ(differs, 0.0) << "the final view is the lit image";
      else EXPECT_GT(differs, 1e-2 * double(shown.size())) << "a view that draws the final image";
      if (view == "indirect") {
        const render::ImageRgba indirect = run.indirect();
        for (size_t i = 0; i < shown.size(); ++i)
          for (int c = 0; c < 3; ++c) ASSERT_EQ(shown[i][c], indirect[i][c]) << "pixel " << i;
      }
    }
  }
}

// The ECS may run more often than the renderer draws: the VPLs on a wall that moved in a frame that was
// never rendered are invalidated all the same, at the next rendered frame (the change sets merge).
TEST_F(RenderTest, ChangesFromFramesThatWereNotRenderedReachTheTechnique) {
  gi::GiSettings s;
  s.technique = "temporal";
  s.temporal.vpl.vpls = 256;
  s.temporal.reshootBudget = 256;
  s.temporal.temporalSets = 1;
  GiRun run(context(), s, "cornell", 64, 64);
  run.update(), run.render();
  const ecs::Entity box = run.named("tall_box");
  ASSERT_FALSE(box.isNull());
  uint32_t onBox = 0;
  for (const gi::PathVpl& v : gi::pathsOf(*run.gi)->vpls()) onBox += v.valid && v.surface == box;
  ASSERT_GT(onBox, 0u) << "the light reaches the box";
  const uint64_t invalidatedBefore = gi::pathsOf(*run.gi)->stats().invalidatedTotal;
  run.world.template write<scene::Transform>(box).translation.x += 0.05f;
  run.update();  // the move, not rendered
  run.update();  // a frame with no change
  run.render();
  EXPECT_GE(gi::pathsOf(*run.gi)->stats().invalidatedTotal - invalidatedBefore, onBox) << "every VPL on the moved box";
}

// GiSystem::reset switches the technique at run time (the sample's panel does): each technique after the
// switch draws what it draws when the GI is made with it, frame for frame, and the first technique,
// switched back to, draws its own image again. The spot moves between the switches, so a part that
// kept the old world's state (a BVH instance, a voxel, a VPL) would show.
TEST_F(RenderTest, SwitchingTechniqueAtRunTimeGivesTheImageOfStartingWithIt) {
  constexpr int kFrames = 6;
  constexpr uint32_t kSize = 64;
  std::vector<gi::GiSettings> order;
  for (const char* name : {"temporal", "many-lights", "vct", "temporal"}) {
    gi::GiSettings s;
    s.technique = name;
    order.push_back(s);
  }
  order[0].temporal.visibility = gi::VisibilityBackend::Bvh;  // the last one, SVO: another voxel scene set-up
  GiRun switched(context(), order[0], "cornell", kSize, kSize);
  for (size_t i = 0; i < order.size(); ++i) {
    SCOPED_TRACE(order[i].technique);
    if (i > 0) {
      switched.world.write<scene::Transform>(switched.named("spot")).translation.x += 0.1f;
      switched.gi->reset(order[i]);
    }
    switched.step(kFrames);
    // A fresh GI with these settings on the same world as it is now.
    GiRun fresh(context(), order[i], "cornell", kSize, kSize);
    fresh.world.write<scene::Transform>(fresh.named("spot")).translation = switched.world.get<scene::Transform>(switched.named("spot")).translation;
    fresh.step(kFrames);
    const render::ImageRgba a = fresh.indirect(), b = switched.indirect();
    const glm::dvec3 lit = render::meanOver(a);
    ASSERT_GT(lit.r + lit.g + lit.b, 1e-3) << "indirect light to compare";
    EXPECT_LT(render::relativeMse(b, a), 1e-6) << "indirect light";
    EXPECT_LT(render::relativeMse(switched.hdr(), fresh.hdr()), 1e-6) << "final image";
    EXPECT_EQ(switched.gi->techniqueEntry().name, std::string(order[i].technique));
  }
  EXPECT_THROW(switched.gi->reset([] { gi::GiSettings s; s.technique = "no_such"; return s; }()), std::invalid_argument);
  EXPECT_EQ(switched.gi->techniqueEntry().name, std::string("temporal")) << "a refused switch changes nothing";

  // GI off at run time (detach) and on again (attach): no indirect light while off; on again, the image
  // of a fresh start, though the world changed while the GI was not watching.
  switched.gi->detach();
  switched.world.write<scene::Transform>(switched.named("spot")).translation.x -= 0.3f;
  switched.step();
  const glm::dvec3 off = render::meanOver(switched.indirect());
  EXPECT_EQ(off.r + off.g + off.b, 0.0) << "no indirect light while detached";
  switched.gi->attach(*switched.renderer);
  switched.step(kFrames);
  GiRun fresh(context(), order.back(), "cornell", kSize, kSize);
  fresh.world.write<scene::Transform>(fresh.named("spot")).translation = switched.world.get<scene::Transform>(switched.named("spot")).translation;
  fresh.step(kFrames);
  EXPECT_LT(render::relativeMse(switched.indirect(), fresh.indirect()), 1e-6) << "attached again";

  // Off, then on with other settings (the panel's path: reset while detached, then attach, one rebuild).
  switched.gi->detach();
  switched.world.write<scene::Transform>(switched.named("spot")).translation.x += 0.2f;
  switched.step();
  switched.gi->reset(order[1]);
  switched.gi->attach(*switched.renderer);
  switched.step(kFrames);
  GiRun fresh2(context(), order[1], "cornell", kSize, kSize);
  fresh2.world.write<scene::Transform>(fresh2.named("spot")).translation = switched.world.get<scene::Transform>(switched.named("spot")).translation;
  fresh2.step(kFrames);
  EXPECT_LT(render::relativeMse(switched.indirect(), fresh2.indirect()), 1e-6) << "reset while off, then attached";
}
