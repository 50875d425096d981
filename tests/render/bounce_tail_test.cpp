// Energy beyond the last bounce (VplOptions::bounceTail, gi_module/shaders/shared/bounce_tail.h): both
// VPL techniques with 1..3 simulated bounces against the path tracer with 8, on the Cornell box with a spot.
// Both gather the tail's probes as one more bounce, scaled to carry every later one (many lights in
// vpl_tail.comp, the temporal technique in TemporalIndirect::prepare). With one bounce the worst region is
// 15% off (temporal) and 17% (many lights); when they scaled their last bounce instead, the temporal
// technique's short box front, lit by later bounces only, was 86% too bright and many lights' 54%.
// Without the tail the tall box's face to the red wall is 56% too dark at one bounce.
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "render/cornell_regions.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 128;
constexpr uint32_t kReferenceBounces = 8;

gi::GiSettings settingsFor(const char* technique, uint32_t bounces, bool tail, uint32_t seed) {
  gi::GiSettings s;
  s.technique = technique;
  gi::VplOptions& v = std::string(technique) == "temporal" ? s.temporal.vpl : s.manyLights.vpl;
  v.seed = seed;
  v.vpls = 1024 * bounces;
  v.bounces = bounces;
  v.bounceTail = tail;
  s.temporal.temporalSets = 1;
  s.temporal.reshootBudget = 1024 * bounces;
  return s;
}

struct Measure {
  double mean = 0;             // whole image's luminance over the reference's
  double worstRegion = 0;      // largest |ratio - 1| over the regions
  std::string worstName;
};

Measure compare(const Frame& f, const render::ImageRgba& ref, const scene::AssetStore& assets, bool print) {
  Measure m;
  m.mean = luminance(render::meanOver(f.hdr)) / luminance(render::meanOver(ref));
  Regions regions = cornellRegions(f, assets, kSize);
  for (auto& [name, mask] : regions.masks) {
    size_t n = 0;
    for (uint8_t b : mask) n += b;
    if (n < 60) continue;
    double a = luminance(render::meanOver(f.hdr, &mask)), b = luminance(render::meanOver(ref, &mask));
    if (print) dyngi::test::report("    %-16s %.4f / %.4f = %.3f\n", name.c_str(), a, b, a / b);
    if (std::abs(a / b - 1.0) > m.worstRegion) m.worstRegion = std::abs(a / b - 1.0), m.worstName = name;
  }
  return m;
}
}  // namespace

TEST_F(RenderTest, BounceTailBringsBothVplTechniquesToThePathTracersManyBounces) {
  render::ImageRgba reference;
  for (const char* technique : {"temporal", "many-lights"})
    for (uint32_t bounces : {1u, 2u, 3u}) {
      Measure off, on;
      for (bool tail : {false, true}) {
        // With 3 bounces the figures are held to a few percent: the mean image of three seeds (one
        // seed's VPLs move the image mean by 1-2 percent, a small face's by more).
        const uint32_t seeds = bounces == 3 ? 3 : 1;
        std::optional<Frame> mean;
        std::optional<GiRun> run;
        for (uint32_t seed = 1; seed <= seeds; ++seed) {
          run.emplace(context(), settingsFor(technique, bounces, tail, seed));
          run->step(3);
          if (reference.empty()) reference = run->pathTraced(256, kReferenceBounces);
          Frame f = run->readFrame();
          if (!mean) mean = std::move(f);
          else
            for (size_t i = 0; i < f.hdr.size(); ++i) mean->hdr[i] += f.hdr[i];
        }
        for (glm::vec4& c : mean->hdr) c /= float(seeds);
        Measure m = compare(*mean, reference, run->assets, bounces == 3);
        dyngi::test::report("%-11s bounces %u tail %-3s: image %.3f of the path tracer's (%u bounces), worst region %s off by %.1f%%\n", technique,
                    bounces, tail ? "on" : "off", m.mean, kReferenceBounces, m.worstName.c_str(), 100 * m.worstRegion);
        (tail ? on : off) = m;
      }
      EXPECT_LT(std::abs(on.mean - 1.0), std::abs(off.mean - 1.0)) << technique << " at " << bounces << " bounce(s)";
      // One bounce, one seed: the probes put the later bounces where the second lands. Temporal 15.3%
      // off at worst (the tall box's face to the red wall; 86% when it scaled its last bounce), many
      // lights 17.0% (the short box's front; 54% then).
      if (bounces == 1) {
        EXPECT_LE(on.worstRegion, 0.20) << technique << ": " << on.worstName;
      }
      if (bounces == 3) {
        EXPECT_LT(off.mean, 0.95) << technique << ": without the tail 3 bounces miss the later ones";  // measured 0.92
        EXPECT_NEAR(on.mean, 1.0, 0.03) << technique;
        // Regions (each within 10 percent). Temporal, its paths' first directions from the R3 sequence, its
        // probes gathered: 4.2% off at worst (the tall box's face to the red wall). Many lights: 5.1% (the
        // short box's front, dark), its seed turning the bounces' Halton points so no error is fixed.
        EXPECT_LE(on.worstRegion, 0.10) << technique << ": " << on.worstName;
      }
    }
}
