// The GI system's temporal VPL technique on automated dynamic scenes.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/gi_system.h"
#include "dyngi/gi/path_tracer.h"
#include "render/cornell_regions.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "testing/gi_probes.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 128;

gi::GiSettings settings(uint32_t T, gi::VisibilityBackend vis = gi::VisibilityBackend::Svo) {
  gi::GiSettings s;
  s.technique = "temporal";
  s.temporal.visibility = vis;
  s.temporal.vpl.vpls = 512;
  // The sets' machinery against all VPLs at once, exact counts of what an edit recolours: one bounce
  // without the tail's probes (bounce_tail_test.cpp has them), whose brighter samples only add noise here.
  s.temporal.vpl.bounceTail = false;
  s.temporal.temporalSets = T;
  s.temporal.reshootBudget = 512;  // fill the pool in the first frame; the sets then take T frames to render,
  s.temporal.catchUpSets = 1;      // one a frame (the schedule these tests reason about; the catch-up has its own)
  return s;
}
double meanLum(const render::ImageRgba& img) {
  glm::dvec3 m = render::meanOver(img);
  return 0.2126 * m.r + 0.7152 * m.g + 0.0722 * m.b;
}
}  // namespace

TEST_F(RenderTest, TemporalAccumulationEqualsAllVplsInOneFrame) {
  GiRun all(context(), settings(1));
  all.step(2);
  render::ImageRgba reference = all.hdr();
  GiRun temporal(context(), settings(16));
  temporal.step(16);
  double rel = render::relativeMse(temporal.hdr(), reference);
  dyngi::test::report("T = 16 after 16 frames vs all 512 VPLs in one frame: relMSE %.5f\n", rel);
  EXPECT_LE(rel, 0.01);
  EXPECT_EQ(gi::temporalOf(*temporal.gi)->setsRendered(), 16u);
}

// Sizes that are no multiple of the 4 x 4 interleave (partial sub-images at the right and bottom
// edges), and a resize in the middle of a run (the per-pixel buffers are laid out per sub-image).
TEST_F(RenderTest, TemporalAccumulationHoldsAtOddSizesAndAfterResize) {
  const std::pair<uint32_t, uint32_t> sizes[] = {{70, 90}, {93, 61}};
  // A narrower view, so that walls and floor reach every edge of the image.
  auto narrow = [](GiRun& run) { run.world.write<scene::Camera>(run.named("camera")).yfov = glm::radians(22.0f); };
  GiRun temporal(context(), settings(4), "cornell", sizes[0].first, sizes[0].second);
  narrow(temporal);
  for (auto [w, h] : sizes) {
    if (w != sizes[0].first) temporal.renderer->resize(w, h);
    temporal.step(4);
    GiRun all(context(), settings(1), "cornell", w, h);
    narrow(all);
    all.step(2);
    render::ImageRgba ref = all.hdr(), got = temporal.hdr();
    double rel = render::relativeMse(got, ref);
    dyngi::test::report("%ux%u: T = 4 after 4 frames vs all VPLs: relMSE %.5f\n", w, h, rel);
    EXPECT_LE(rel, 0.01) << w << "x" << h;
    // The last column and row (partial sub-images) hold the same light: the filter's window stays
    // inside the image and takes one pixel of every sub-image there too. (A clamped window repeated
    // the border pixel's sub-image and left another out: the border was 12% off at 93x61, since the
    // sub-images' VPL subsets differ between T = 1 and T = 4; with the window inside, 0.2-2%.)
    auto lum = [w = w](const render::ImageRgba& im, uint32_t x, uint32_t y) {
      const glm::vec4& p = im[size_t(y) * w + x];
      return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    };
    double edge = 0.0, refEdge = 0.0;
    for (uint32_t y = 0; y < h; ++y) edge += lum(got, w - 1, y), refEdge += lum(ref, w - 1, y);
    for (uint32_t x = 0; x < w; ++x) edge += lum(got, x, h - 1), refEdge += lum(ref, x, h - 1);
    dyngi::test::report("  last row + column: %.4f vs %.4f\n", edge, refEdge);
    ASSERT_GT(refEdge, 0.1 * double(w + h) * 0.05) << "the border must show lit geometry for this check to mean anything";
    EXPECT_NEAR(edge, refEdge, 0.05 * refEdge) << "edge pixels of " << w << "x" << h;
  }
}

// With a still camera the gather updates each pixel's running sum in O(1) and queues only the pixels
// whose surface changed for the full reprojection (temporal_reproject.comp). The result must be what
// reprojecting every pixel from every set gives, here while a box turns and slides every frame.
TEST_F(RenderTest, IncrementalAccumulationEqualsFullReprojection) {
  const uint32_t T = 4;
  GiRun incremental(context(), settings(T)), full(context(), settings(T));
  gi::temporalOf(*full.gi)->settings().incrementalAccumulation = false;
  double worst = 0.0;
  for (int f = 0; f < 12; ++f) {
    for (GiRun* run : {&incremental, &full}) {
      auto& t = run->world.write<scene::Transform>(run->named("tall_box"));
      t.rotation = glm::angleAxis(0.08f * float(f), glm::vec3(0, 1, 0));
      t.translation.x += 0.01f;
      run->step();
    }
    render::ImageRgba a = incremental.indirect(), b = full.indirect();
    ASSERT_GT(meanLum(b), 0.0);
    worst = std::max(worst, render::relativeMse(a, b));
  }
  dyngi::test::report("incremental vs full reprojection, moving box: worst relMSE %.2e\n", worst);
  EXPECT_LT(worst, 1e-6);
}

TEST_F(RenderTest, CameraMotionStaysCloseAndNeverLeavesHoles) {
  GiRun run(context(), settings(8));
  run.step(10);
  ecs::Entity cam{};
  run.world.each<scene::ActiveCamera>([&](ecs::Entity e, const scene::ActiveCamera&) { cam = e; });
  double worst = 0;
  for (int f = 0; f < 8; ++f) {
    auto& t = run.world.write<scene::Transform>(cam);
    t.translation.x += 0.06f;
    t.rotation = glm::angleAxis(-0.025f * float(f + 1), glm::vec3(0, 1, 0));
    run.step();
    render::ImageRgba moving = run.hdr(), movingIndirect = run.indirect();
    // The converged image at this camera: all VPLs at once, same pool (same seed, filled at once).
    GiRun ref(context(), settings(1));
    ref.world.write<scene::Transform>(ref.named("camera")) = run.world.get<scene::Transform>(cam);
    ref.step(2);
    render::ImageRgba converged = ref.hdr(), convergedIndirect = ref.indirect();
    double rel = render::relativeMse(moving, converged);
    worst = std::max(worst, rel);
    int holes = 0;
    for (size_t i = 0; i < converged.size(); ++i)
      holes += convergedIndirect[i].r + convergedIndirect[i].g > 0.01f && movingIndirect[i].r + movingIndirect[i].g == 0.0f;
    EXPECT_EQ(holes, 0) << "frame " << f << ": indirect light never drops to black where it exists";
  }
  dyngi::test::report("camera motion: worst relMSE against the converged image %.4f\n", worst);
  EXPECT_LT(worst, 0.03);
}

TEST_F(RenderTest, LightOffDrivesIndirectToZeroAndBack) {
  const uint32_t T = 8;
  GiRun run(context(), settings(T));
  run.step(T + 2);
  double on = meanLum(run.indirect());
  ASSERT_GT(on, 0.0);
  ecs::Entity light = run.named("spot");
  run.world.write<scene::Light>(light).enabled = false;
  run.step(int(T));
  double off = meanLum(run.indirect());
  dyngi::test::report("mean indirect: on %.5f, %u frames after switching off %.6f\n", on, T, off);
  EXPECT_LT(off, 1e-6 * on) << "zero up to the float rounding of the running sums";
  run.world.write<scene::Light>(light).enabled = true;
  run.step(int(T) + 1);
  double back = meanLum(run.indirect());
  dyngi::test::report("back on after %u frames: %.5f\n", T + 1, back);
  // Fresh VPLs are a new Monte Carlo sample of the same light: equal within the noise of 512 VPLs.
  EXPECT_NEAR(back / on, 1.0, 0.10);
}

TEST_F(RenderTest, MovedObjectChangesIndirectWherePathTracerSays) {
  const uint32_t T = 4;
  gi::GiSettings s = settings(T);
  s.temporal.vpl.vpls = 2048;
  GiRun run(context(), s);
  run.step(T + 1);
  render::ImageRgba before = run.indirect();
  gi::EmbreeScene bvh;
  auto pathTraced = [&] {
    bvh.sync(run.world, run.assets, 0);
    gi::PathTracerSettings pts;
    pts.spp = 256;
    pts.bounces = 1;
    pts.pixelJitter = false;
    return gi::pathTrace(render::extractSnapshot(run.world, run.assets, 0), bvh, run.assets, kSize, kSize, pts);
  };
  render::ImageRgba ptBefore = pathTraced();
  render::ImageRgba hdrBefore = run.hdr();
  // Slide the tall box to the middle of the room.
  ecs::Entity box = run.named("tall_box");
  run.world.write<scene::Transform>(box).translation = {0.15f, 0.6f, -0.1f};
  run.step(T + 1);
  render::ImageRgba hdrAfter = run.hdr();
  render::ImageRgba ptAfter = pathTraced();
  // Compare the change in 8x8 blocks (means), where the path tracer's noise averages out.
  std::vector<double> ours, truth;
  for (uint32_t by = 0; by < kSize; by += 8)
    for (uint32_t bx = 0; bx < kSize; bx += 8) {
      double a = 0, b = 0;
      for (uint32_t y = by; y < by + 8; ++y)
        for (uint32_t x = bx; x < bx + 8; ++x) {
          size_t i = size_t(y) * kSize + x;
          a += double(hdrAfter[i].g - hdrBefore[i].g);
          b += double(ptAfter[i].g - ptBefore[i].g);
        }
      ours.push_back(a / 64), truth.push_back(b / 64);
    }
  double ma = 0, mb = 0;
  for (size_t i = 0; i < ours.size(); ++i) ma += ours[i], mb += truth[i];
  ma /= double(ours.size()), mb /= double(ours.size());
  double cov = 0, va = 0, vb = 0;
  for (size_t i = 0; i < ours.size(); ++i) {
    cov += (ours[i] - ma) * (truth[i] - mb);
    va += (ours[i] - ma) * (ours[i] - ma);
    vb += (truth[i] - mb) * (truth[i] - mb);
  }
  double corr = cov / std::sqrt(va * vb);
  dyngi::test::report("moved box: correlation of the image change with the path tracer's change: %.3f\n", corr);
  EXPECT_GT(corr, 0.9);
  // And the indirect light itself changed (not just the direct light of the moved box).
  render::ImageRgba after = run.indirect();
  double changed = 0;
  for (size_t i = 0; i < after.size(); ++i) changed += std::abs(double(after[i].g - before[i].g));
  EXPECT_GT(changed / double(after.size()), 1e-3);
}

TEST_F(RenderTest, SvoAndBvhVisibilityGiveTheSameImage) {
  GiRun svo(context(), settings(4, gi::VisibilityBackend::Svo));
  GiRun bvh(context(), settings(4, gi::VisibilityBackend::Bvh));
  svo.step(5);
  bvh.step(5);
  double rel = render::relativeMse(svo.hdr(), bvh.hdr());
  dyngi::test::report("svo vs bvh visibility: relMSE %.5f\n", rel);
  EXPECT_LT(rel, 0.005);
}

// The default technique (incremental temporal VPL paths) in absolute terms: once every temporal set is
// filled, each wall's and box face's mean radiance and the whole image's relMSE against the reference
// path tracer at the same bounce count, for each kind of light.
TEST_F(RenderTest, TemporalPathsMatchPathTracerPerRegionForEveryLightType) {
  struct Case {
    const char* name;
    scene::LightType type;
    float intensity;
    glm::vec3 position, direction;  // direction: where the light points
  };
  const Case cases[] = {
      {"spot", scene::LightType::Spot, sample::CornellLayout::kSpotIntensity, {0, 1.9f, 0}, {0, -1, 0}},
      {"point", scene::LightType::Point, 3.0f, {0.2f, 1.6f, 0.1f}, {0, -1, 0}},
      // The box is open towards +z: the sun comes in through the opening, from above and to the right.
      {"directional", scene::LightType::Directional, 4.0f, {0, 0, 0}, glm::normalize(glm::vec3(-0.35f, -0.55f, -1.0f))},
  };
  for (const Case& c : cases) {
    gi::GiSettings s = settings(4);
    s.temporal.vpl.vpls = 1024;
    s.temporal.reshootBudget = 1024;
    GiRun run(context(), s);
    ecs::Entity light{};
    run.world.each<scene::Light>([&](ecs::Entity e, const scene::Light&) { light = e; });
    {
      scene::Light& l = run.world.write<scene::Light>(light);
      l.type = c.type;
      l.intensity = c.intensity;
      scene::Transform& t = run.world.write<scene::Transform>(light);
      t.translation = c.position;
      t.rotation = glm::rotation(glm::vec3(0, 0, -1), c.direction);  // lights shine along local -Z
    }
    run.step(6);  // 4 sets, one frame each, after the pool is filled
    const Frame f = run.readFrame();
    const render::ImageRgba ref = run.pathTraced(512, 1);

    Regions regions = cornellRegions(f, run.assets, kSize);
    ASSERT_GE(regions.masks.size(), 6u) << c.name;
    double brightest = 0;
    for (auto& [name, mask] : regions.masks) brightest = std::max(brightest, luminance(render::meanOver(ref, &mask)));
    double worst = 0;
    std::string worstRegion;
    for (auto& [name, mask] : regions.masks) {
      size_t n = 0;
      for (uint8_t m : mask) n += m;
      double b = luminance(render::meanOver(ref, &mask));
      if (n < 60 || b < 1e-3) continue;  // too small to average, or unlit (the directional case's hidden faces)
      double a = luminance(render::meanOver(f.hdr, &mask));
      // Regions lit directly (at least a tenth of the brightest) hold to 10%. Dim regions lit almost only
      // by bounced light hold to 35%: there 1024 clamped VPLs leave 10-27% errors today (measured: the
      // tall box's face to the red wall, the short box's front under the point light, the green wall
      // under the sun): the clamped VPLs' artifacts.
      const double tolerance = b >= 0.1 * brightest ? 0.10 : 0.35;
      dyngi::test::report("%-11s %-16s temporal %.4f  path %.4f  ratio %.3f  (%zu px, tolerance %.0f%%)\n", c.name, name.c_str(), a, b, a / b, n,
                  100 * tolerance);
      if (std::abs(a / b - 1.0) > worst) worst = std::abs(a / b - 1.0), worstRegion = name;
      EXPECT_NEAR(a / b, 1.0, tolerance) << c.name << ": " << name;
    }
    double rel = render::relativeMse(f.hdr, ref);
    dyngi::test::report("%-11s relMSE %.4f, worst region %s off by %.1f%%\n", c.name, rel, worstRegion.c_str(), 100 * worst);
    EXPECT_LE(rel, 0.04) << c.name;  // measured 0.0042 (spot), 0.0055 (point), 0.0251 (directional)
  }
}

// A material edit changes what a surface reflects, not where light goes: the VPLs lying on the edited
// surface and every later bounce of their paths keep their positions and take the new colour in the same
// frame; every other VPL stays exactly as it was. Then the indirect light follows the new colour where the
// path tracer says it does. (Reshooting those VPLs instead, which the first version of this change did,
// leaves the surface with only the share of new samples that land on it again: the ceiling's blue/red
// then moved 0.956 -> 0.997 where the reference moves 0.947 -> 1.056.)
TEST_F(RenderTest, MaterialEditRecoloursTheVplsOnThatSurfaceAndTheLightFollows) {
  gi::GiSettings s = settings(4);
  s.temporal.vpl.vpls = 1024;
  s.temporal.vpl.bounces = 2;
  s.temporal.reshootBudget = 1024;
  GiRun run(context(), s);
  run.step(6);
  const gi::VplPaths& paths = *gi::pathsOf(*run.gi);
  const std::vector<gi::PathVpl> before = paths.vpls();
  const std::vector<uint32_t> shotBefore = paths.reshootCounts();
  const ecs::Entity wall = run.named("left_wall_red");
  ASSERT_FALSE(wall.isNull());
  // Expected: on the wall, or a later bounce of a path that touched it.
  std::vector<bool> expect(before.size(), false);
  uint32_t expected = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    const bool inheritsFromParent = i % s.temporal.vpl.bounces > 0 && expect[i - 1];
    expect[i] = before[i].valid && (inheritsFromParent || (before[i].placed && before[i].surface == wall));
    expected += expect[i];
  }
  ASSERT_GT(expected, 50u) << "the red wall holds a fair share of the VPLs";

  const render::ImageRgba hdrBefore = run.hdr();
  const glm::vec3 blue(0.1f, 0.2f, 0.8f), red(0.63f, 0.065f, 0.05f);
  run.world.write<scene::Material>(wall).baseColor = glm::vec4(blue, 1.0f);
  run.step(1);
  EXPECT_EQ(paths.stats().refreshedThisFrame, expected);
  EXPECT_EQ(paths.stats().invalidatedThisFrame, 0u) << "no path is thrown away";
  uint32_t wrong = 0;
  for (uint32_t i = 0; i < before.size(); ++i) {
    const gi::PathVpl& v = paths.vpls()[i];
    wrong += paths.reshootCounts()[i] != shotBefore[i];
    wrong += v.position != before[i].position;
    if (!expect[i]) wrong += v.flux != before[i].flux;
    else if (before[i].placed && before[i].surface == wall && i % s.temporal.vpl.bounces == 0)
      wrong += glm::any(glm::greaterThan(glm::abs(v.flux - before[i].flux / red * blue), 1e-5f * glm::vec3(1.0f) + 1e-4f * v.flux));
  }
  EXPECT_EQ(wrong, 0u) << "exactly the wall's VPLs and their later bounces took the new colour, nothing was reshot";

  // After a full cycle of the temporal sets the bounced light has turned from red to blue where the path
  // tracer says it does: every region whose colour the reference sees move by over 5% moves the same
  // way, and the wall itself (its own albedo under direct and bounced light) matches the reference.
  run.step(4);
  const Frame f = run.readFrame();
  const render::ImageRgba refAfter = run.pathTraced(256, 2);
  run.world.write<scene::Material>(wall).baseColor = glm::vec4(red, 1.0f);  // the reference before
  const render::ImageRgba refBefore = run.pathTraced(256, 2);
  Regions regions = cornellRegions(f, run.assets, kSize);
  auto blueOverRed = [&](const render::ImageRgba& img, const std::vector<uint8_t>& mask) {
    glm::dvec3 c = render::meanOver(img, &mask);
    return c.b / c.r;
  };
  int followed = 0;
  for (auto& [name, mask] : regions.masks) {
    const double oursBefore = blueOverRed(hdrBefore, mask), oursAfter = blueOverRed(f.hdr, mask);
    const double refB = blueOverRed(refBefore, mask), refA = blueOverRed(refAfter, mask);
    dyngi::test::report("%-13s blue/red  temporal %.3f -> %.3f   path %.3f -> %.3f\n", name.c_str(), oursBefore, oursAfter, refB, refA);
    if (refA > 1.05 * refB) {
      // Measured: 0.68-1.13 of the reference's change (0.38 on the ceiling when the VPLs were reshot).
      EXPECT_NEAR((oursAfter - oursBefore) / (refA - refB), 1.0, 0.5) << name << " turns bluer as much as in the reference";
      ++followed;
    }
  }
  EXPECT_GE(followed, 5) << "the edit is seen beyond the wall itself";
  EXPECT_NEAR(blueOverRed(f.hdr, regions.masks.at("red wall")) / blueOverRed(refAfter, regions.masks.at("red wall")), 1.0, 0.05);
}

// The merge filter without tiles: one VPL lights the back wall through one sub-image of the
// K x K interleaving only. A K x K box filter turns that sub-image's samples into K x K plateaus (each
// pixel takes the one sample in its window: most horizontal neighbours equal), the
// "tiles" around hot VPLs. The separable tent of width 2K - 1 (filter_tent.glsl) interpolates between the
// samples instead: no plateaus, and the light still sums every sub-image with equal weight. (Measured
// with the box put back in filter_tent.glsl: 242 of 434 neighbour pairs equal; with the tent, none.)
TEST_F(RenderTest, MergeFilterInterpolatesASubImageInsteadOfMakingTiles) {
  gi::GiSettings s = settings(1);
  s.temporal.vpl.vpls = 1;
  s.temporal.reshootBudget = 1;
  s.temporal.vpl.interleave = 4;
  s.temporal.vpl.distanceClamp = 0.01f;   // the filter alone: the VPL's light as it was measured,
  s.temporal.vpl.clampCompensation = 0;    // without the corners' compensation (its own test)
  s.temporal.vpl.seed = 4;                // whose one path's VPL lands where it lights the back wall
  GiRun run(context(), s);
  run.step(3);
  const Frame f = run.readFrame();
  const render::ImageRgba indirect = run.indirect();
  const Regions regions = cornellRegions(f, run.assets, kSize);
  ASSERT_TRUE(regions.masks.count("back wall"));
  const std::vector<uint8_t>& wall = regions.masks.at("back wall");
  size_t pairs = 0, equal = 0;
  double peak = 0;
  for (size_t i = 0; i < indirect.size(); ++i) peak = std::max(peak, double(wall[i] ? indirect[i].g : 0.0f));
  ASSERT_GT(peak, 0.0) << "the VPL lights the back wall";
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x + 1 < kSize; ++x) {
      const size_t i = size_t(y) * kSize + x;
      if (!wall[i] || !wall[i + 1] || indirect[i].g < 0.05 * peak) continue;
      ++pairs;
      equal += std::abs(indirect[i].g - indirect[i + 1].g) <= 1e-6f * float(peak);
    }
  dyngi::test::report("back wall: %zu lit neighbour pairs, %zu equal (a K x K box in its place: 242 of 434)\n", pairs, equal);
  ASSERT_GT(pairs, 200u);
  EXPECT_LT(double(equal) / double(pairs), 0.1);
}
