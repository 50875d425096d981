// The GI budget on the real renderer: every technique's quality knobs keep the image's light where it
// was (a knob trades noise for time, never energy), and the GI system wires the controller to the
// measured cost: a budget no level can meet drives every knob to its floor and says so, a generous one
// changes nothing, and it reads a cost the device spends (fenced frames where timestamps miss work). How
// well it holds a budget is measured by scripts/budget_run.sh, not here (timing).
#include <gtest/gtest.h>

#include "support/report.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 64;
constexpr int kFrames = 36;  // two full rounds of 16 temporal sets, and some
constexpr uint32_t kSeeds = 4;

gi::GiSettings settingsFor(const gi::TechniqueEntry& e, uint32_t vpls) {
  gi::GiSettings s;
  s.technique = e.name;
  for (const gi::OptionRef& r : e.options(s))
    if (std::string_view(r.spec->name) == "vpls") r.set(vpls);
  return s;
}
}  // namespace

TEST_F(RenderTest, EveryQualityKnobAtItsFloorKeepsTheMeanIndirectLight) {
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    SCOPED_TRACE(e.name);
    // At the floor an eighth of the VPLs light the image, so one run's mean is off by several percent
    // by chance (which eighth): the ratio to the same seed's full run is averaged over four seeds.
    double meanRatio = 0;
    // A technique without random numbers (voxel cone tracing) gives the same figure for every seed.
    bool seeded = false;
    {
      gi::GiSettings probe;
      for (const gi::OptionRef& r : e.options(probe)) seeded |= std::string_view(r.spec->name) == "seed";
    }
    const uint32_t seeds = seeded ? kSeeds : 1;
    for (uint32_t seed = 1; seed <= seeds; ++seed) {
      gi::GiSettings s = settingsFor(e, 1024);
      s.temporal.vpl.seed = s.manyLights.vpl.seed = seed;
      GiRun full(context(), s, "cornell", kSize, kSize);
      full.step(kFrames);
      const double fullMean = luminance(render::meanOver(full.indirect()));
      ASSERT_GT(fullMean, 0.0);
      GiRun lowered(context(), s, "cornell", kSize, kSize);
      const std::vector<gi::QualityKnob> knobs = lowered.gi->technique().qualityKnobs();
      ASSERT_FALSE(knobs.empty()) << "a technique a budget can act on";
      for (const gi::QualityKnob& k : knobs) {
        ASSERT_GE(k.levels.size(), 2u) << k.name;
        EXPECT_LE(k.levels.back(), k.levels.front() / 4) << k.name << ": the floor saves something";
        k.apply(k.levels.back());
      }
      lowered.step(kFrames);
      const double mean = luminance(render::meanOver(lowered.indirect()));
      dyngi::test::report("knob floor| %s seed %u: mean indirect %.5f with every VPL, %.5f at the floor (%+.1f%%)\n", e.name, seed, fullMean, mean,
                  100 * (mean / fullMean - 1));
      meanRatio += mean / fullMean / seeds;
    }
    // Fewer VPLs gathered, each sub-image's sum scaled to stand for all of them: the same light, noisier.
    // Today -2.7 percent (temporal; over ten seeds -0.5) and -1.2 (many lights). Without the scaling it
    // would be -87 percent; with a sub-image left without VPLs (a floor under K^2) it was -6.7.
    EXPECT_NEAR(meanRatio, 1.0, 0.04);
  }
}

TEST_F(RenderTest, AGiBudgetDrivesTheKnobsFromTheMeasuredCost) {
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    SCOPED_TRACE(e.name);
    // No level can meet 1 microsecond: every knob ends at its floor and the budget is reported unmet.
    gi::GiSettings tight = settingsFor(e, 512);
    tight.budget.budgetMs = 0.001f;
    GiRun run(context(), tight, "cornell", kSize, kSize);
    size_t oneOff = 0;  // frames with one-off work (the temporal technique's catch-up at the start)
    for (int i = 0; i < kFrames; ++i) {
      run.step();
      oneOff += run.gi->technique().lastFrameWasOneOff();
    }
    const gi::BudgetController* b = run.gi->budget();
    ASSERT_NE(b, nullptr);
    EXPECT_GT(run.gi->stats().giMs, 0.0) << "the GI's cost is measured";
    EXPECT_EQ(b->measured().size(), size_t(kFrames) - oneOff) << "every rendered frame is measured, but for one-off ones";
    if (e.name == std::string("temporal")) {
      EXPECT_GT(oneOff, 0u) << "the sets are caught up at the start";
    }
    EXPECT_EQ(b->level(), b->floorLevel());
    EXPECT_FALSE(b->budgetMet());
    const std::vector<gi::QualityKnob> knobs = run.gi->technique().qualityKnobs();
    ASSERT_EQ(b->knobValues().size(), knobs.size());
    // The technique uses the floor value (its stats report what it used: a key named as the knob, or the
    // many-lights technique's VPL count).
    double used = -1.0;
    for (const auto& [section, values] : run.gi->technique().statsSections())
      for (const auto& [key, value] : values)
        if (key == b->knobValues().front().first || (section == "vpl" && key == "count" && used < 0.0)) used = value;
    EXPECT_EQ(used, b->knobValues().front().second);

    // Ten seconds a frame: nothing to lower.
    gi::GiSettings generous = settingsFor(e, 512);
    generous.budget.budgetMs = 10000.0f;
    GiRun easy(context(), generous, "cornell", kSize, kSize);
    easy.step(kFrames);
    ASSERT_NE(easy.gi->budget(), nullptr);
    EXPECT_EQ(easy.gi->budget()->level(), 0u);
    EXPECT_TRUE(easy.gi->budget()->changes().empty());
    EXPECT_TRUE(easy.gi->budget()->budgetMet());
  }
  // Off by default.
  GiRun off(context(), gi::GiSettings{}, "cornell", kSize, kSize);
  EXPECT_EQ(off.gi->budget(), nullptr);
}

// Timestamps that miss part of the GI's work (lavapipe's miss compute passes) would have the budget hold
// a cost the device does not spend. After a few frames a fenced check frame gives the verdict: the
// timestamps written beside the fences bracketing under 0.85 of the fenced cost means every later frame is
// fenced, and the renderer times it so; above, the timestamps stay. (On lavapipe at 256^2 and more they
// bracket about half of VCT's cost in the sample: scripts/budget_run.sh; here the verdict is the device's.)
TEST_F(RenderTest, AGiBudgetReadsTheCostTheDeviceSpends) {
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    SCOPED_TRACE(e.name);
    gi::GiSettings s = settingsFor(e, 256);
    s.budget.budgetMs = 10000.0f;
    GiRun run(context(), s, "cornell", 4 * kSize, 4 * kSize);
    EXPECT_EQ(run.renderer->stageTiming(), render::GpuTimer::Mode::Timestamps);
    run.step(20);
    const gi::GiStats st = run.gi->stats();
    ASSERT_FALSE(st.budgetTiming.empty()) << "no verdict after 20 frames";
    ASSERT_GT(st.timestampCoverage, 0.0);
    dyngi::test::report("%s: timestamps cover %.2f of the fenced GI cost: the budget reads %s\n", e.name, st.timestampCoverage, st.budgetTiming.c_str());
    const bool fenced = st.timestampCoverage < gi::GiSystem::kMinTimestampCoverage;
    EXPECT_EQ(st.budgetTiming, fenced ? "fenced" : "timestamps");
    EXPECT_EQ(run.renderer->stageTiming(), fenced ? render::GpuTimer::Mode::Fenced : render::GpuTimer::Mode::Timestamps)
        << "the renderer times the frames the budget reads";
  }
  // Without a budget nothing is checked and the renderer keeps its timing.
  GiRun off(context(), gi::GiSettings{}, "cornell", kSize, kSize);
  off.step(16);
  EXPECT_TRUE(off.gi->stats().budgetTiming.empty());
  EXPECT_EQ(off.renderer->stageTiming(), render::GpuTimer::Mode::Timestamps);
}
