// Voxel cone tracing (`--gi vct`) against the reference path tracer, its CPU twins and analytic cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <tuple>

#include "support/report.h"
#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/gi/gi_system.h"
#include "techniques/vct/vct_cpu.h"
#include "techniques/vct/voxel_cone_tracing.h"
#include "gpu_aliases.h"
#include "techniques/vct/shaders/vct_shared.h"
#include "render/cornell_regions.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "support/shared_scenes.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "scenes/builtin_scenes.h"
#include <glm/gtc/quaternion.hpp>

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 128;

gi::GiSettings vctSettings() {
  gi::GiSettings s;
  s.technique = "vct";
  s.voxels.resolution = 128;
  if (const char* e = std::getenv("VCT_SPEC")) s.vct.specular = std::atoi(e) != 0;
  if (const char* e = std::getenv("VCT_ANISO")) s.vct.anisotropic = std::atoi(e) != 0;
  if (const char* e = std::getenv("VCT_SCALE")) s.vct.traceScale = std::atoi(e);
  if (const char* e = std::getenv("VCT_CONES")) s.vct.diffuseCones = std::atoi(e);
  if (const char* e = std::getenv("VCT_OFFSET")) s.vct.coneOffset = float(std::atof(e));
  if (const char* e = std::getenv("VCT_STEP")) s.vct.coneStep = float(std::atof(e));
  if (const char* e = std::getenv("VCT_RES")) s.voxels.resolution = uint32_t(std::atoi(e));
  if (const char* e = std::getenv("VCT_REACH")) s.vct.maxDistance = float(std::atof(e));
  if (const char* e = std::getenv("VCT_FILTER")) s.vct.diffuseFilterRadius = uint32_t(std::atoi(e));
  if (const char* e = std::getenv("VCT_FRAMES")) s.vct.traceFrames = uint32_t(std::atoi(e));
  if (const char* e = std::getenv("VCT_INTERLEAVE")) s.vct.coneInterleave = uint32_t(std::atoi(e));
  if (const char* e = std::getenv("VCT_NARROW")) s.vct.farNarrowing = float(std::atof(e));
  return s;
}

[[maybe_unused]] gi::VoxelConeTracing& vctOf(GiRun& run) {
  auto features = run.gi->technique().features();
  return *static_cast<gi::VoxelConeTracing*>(features.at(0));
}

void dump(const std::string& name, const render::ImageRgba& img, uint32_t w, uint32_t h) { dumpTestImage(name, img, w, h); }

double lum(const glm::dvec3& c) { return luminance(c); }

// The path tracer's Cornell box at the test size, once per bounce count (shared by the tests here).
const render::ImageRgba& cornellReference(GiRun& run, uint32_t bounces) {
  static std::map<uint32_t, render::ImageRgba> cache;
  auto it = cache.find(bounces);
  if (it != cache.end()) return it->second;
  // The 2-bounce reference only ranks two images; the full transport's (8) is judged on its tail too.
  return cache[bounces] = run.pathTraced(bounces == 1 ? 512 : bounces >= 8 ? 1024 : 256, bounces);
}
}  // namespace

TEST_F(RenderTest, VctCornellMatchesPathTracerPerRegionWithColourBleeding) {
  // The path tracer is Lambert only: the specular cone (4 percent of the bright floor on the walls) would
  // add 2-5 percent to the walls that the reference cannot have.
  gi::GiSettings s = vctSettings();
  s.vct.specular = false;
  // The defaults split 12 cones between alternate rows of traced pixels (VctOptions::coneInterleave);
  // the filter brings them together. Every pixel marching all 12 is the image the split must reproduce,
  // region by region, without being that image (the rows do march different cones).
  gi::GiSettings everyCone = s;
  everyCone.vct.coneInterleave = 1;
  std::map<std::string, double> firstRatios;
  std::vector<render::ImageRgba> images;
  for (const auto& [label, settings] : {std::pair<const char*, gi::GiSettings>{"default", s}, {"every cone on every pixel", everyCone}}) {
    SCOPED_TRACE(label);
    dyngi::test::report("%s\n", label);
    GiRun run(context(), settings, "cornell", kSize, kSize);
    run.step(4);
    Frame f = run.readFrame();
    const render::ImageRgba& ref = cornellReference(run, 1);
    images.push_back(f.hdr);
    if (settings.vct.coneInterleave == s.vct.coneInterleave) {
      dump("vct_cornell", f.hdr, kSize, kSize);
      dump("vct_cornell_path", ref, kSize, kSize);
      dump("vct_cornell_indirect", run.indirect(), kSize, kSize);
      dump("vct_cornell_direct", run.pathTraced(16, 0), kSize, kSize);
    }
    Regions regions = cornellRegions(f, run.assets, kSize);
    ASSERT_GE(regions.masks.size(), 9u);
    for (auto& [name, mask] : regions.masks) {
      size_t n = 0;
      for (uint8_t m : mask) n += m;
      if (n < 60) continue;
      const double a = lum(render::meanOver(f.hdr, &mask)), b = lum(render::meanOver(ref, &mask));
      dyngi::test::report("%-16s vct %.4f  path %.4f  ratio %.3f  (%zu px)\n", name.c_str(), a, b, a / b, n);
      // The goal: 20 percent for every region. The tight one is the tall box's face to the red
      // wall (96 pixels in its own shadow): 0.82 (0.86 with 6 wide cones and no far narrowing, session
      // 27's defaults), where six cones the same on every pixel gave 0.53 (the light it gets comes
      // between them; VctTurnedConesApproachADenseConeSet). It is the region most sensitive to the far
      // samples' footprints: whole mip levels for footprints of 11-22 voxels took it to 0.66, the far
      // narrowing with 6 cones to 0.68 (vct_cone.glsl's vctReadLevel).
      EXPECT_NEAR(a / b, 1.0, 0.20) << name;
      // The rows' halves of the cone set, filtered, against every cone on every pixel: the scale of a
      // half's light (all the cones' weight over its own) and the filter's balance of the halves.
      if (firstRatios.count(name))
        EXPECT_NEAR(firstRatios[name] / (a / b), 1.0, 0.03) << name << ": interleaved cones against every cone";
      else
        firstRatios[name] = a / b;
    }
    const double rel = render::relativeMse(f.hdr, ref);
    dyngi::test::report("relMSE %.4f\n", rel);
    EXPECT_LE(rel, 0.05);
    auto redness = [&](const render::ImageRgba& img, const char* face) {
      const glm::dvec3 c = render::meanOver(img, &regions.masks.at(face));
      return c.r / c.g;
    };
    ASSERT_TRUE(regions.masks.count("tall_box -x") && regions.masks.count("tall_box +z"));
    const double ours = redness(f.hdr, "tall_box -x") / redness(f.hdr, "tall_box +z");
    const double theirs = redness(ref, "tall_box -x") / redness(ref, "tall_box +z");
    dyngi::test::report("colour bleeding (red/green of the face to the red wall over the front face): vct %.3f path %.3f\n", ours, theirs);
    EXPECT_GT(ours, 1.2) << "the face turned to the red wall is redder";
    EXPECT_NEAR(ours / theirs, 1.0, 0.2);
  }
  ASSERT_EQ(images.size(), 2u);
  const double splitAgainstEvery = render::relativeMse(images[0], images[1]);
  dyngi::test::report("rows' halves against every cone on every pixel: relMSE %.6f\n", splitAgainstEvery);
  EXPECT_GT(splitAgainstEvery, 1e-7) << "the rows march half the cones each, not all of them";
  EXPECT_LT(splitAgainstEvery, 0.001);
}

// Few cones, turned per pixel and filtered, against many: six cones the same on every pixel see the same
// few directions over a whole face, so walls show blotches (coarse texels passing through a cone) and a
// face whose light comes from between two cones goes dark. Each traced pixel turning its set and the
// filter averaging its neighbours must come closer to a dense, fixed set of 32 cones (the same volume,
// a far finer quadrature of the hemisphere) than the fixed six do, in the tail and overall.
TEST_F(RenderTest, VctTurnedConesApproachADenseConeSet) {
  auto indirect = [&](uint32_t cones, uint32_t radius) {
    gi::GiSettings s = vctSettings();
    s.vct.diffuseCones = cones;
    s.vct.diffuseFilterRadius = radius;
    GiRun run(context(), s, "cornell", kSize, kSize);
    run.step(3);
    return run.indirect();
  };
  const render::ImageRgba dense = indirect(32, 0), fixed = indirect(6, 0), turned = indirect(6, gi::VctOptions{}.diffuseFilterRadius);
  dump("vct_cones_dense", dense, kSize, kSize);
  dump("vct_cones_fixed", fixed, kSize, kSize);
  dump("vct_cones_turned", turned, kSize, kSize);
  const double relFixed = render::relativeMse(fixed, dense), relTurned = render::relativeMse(turned, dense);
  const double p99Fixed = render::relativeLuminanceErrorQuantile(fixed, dense, 0.99);
  const double p99Turned = render::relativeLuminanceErrorQuantile(turned, dense, 0.99);
  dyngi::test::report("against 32 fixed cones: 6 fixed relMSE %.4f p99 %.3f; 6 turned and filtered relMSE %.4f p99 %.3f\n", relFixed,
              p99Fixed, relTurned, p99Turned);
  EXPECT_GT(relFixed, 0.008) << "the fixed six are far from the dense set (else this test shows nothing)";
  EXPECT_LT(relTurned, 0.4 * relFixed);
  EXPECT_LT(p99Turned, 0.6 * p99Fixed);
}

// The trace spread over frames (trace-frames 4: a quarter of the traced pixels a frame, the rest carried
// over from the frame before at their surface point). Against the every-frame trace, its truth:
//  - a still view: once every pixel has had its turn the image is the every-frame one, bit for bit;
//  - a camera pan: the carried-over values follow their surfaces, so the image stays close to the
//    every-frame trace of the same frame. Measured here: relMSE 0.0003, p99 0.32; against the every-frame
//    image of 3 frames before, 0.029 and 17.
TEST_F(RenderTest, VctTraceSpreadOverFramesMatchesTheEveryFrameTrace) {
  constexpr int kFrames = 12;
  constexpr float kDegreesPerFrame = 0.5f;  // 1.4 pixels a frame at 128^2
  auto pan = [&](uint32_t traceFrames, bool moving) {
    gi::GiSettings s = vctSettings();
    s.vct.traceFrames = traceFrames;
    GiRun run(context(), s, "cornell", kSize, kSize);
    ecs::Entity camera{};
    run.world.each<scene::ActiveCamera>([&](ecs::Entity e, const scene::ActiveCamera&) { camera = e; });
    const glm::quat start = run.world.get<scene::Transform>(camera).rotation;
    std::vector<render::ImageRgba> frames;
    for (int i = 0; i < kFrames; ++i) {
      if (moving)
        run.world.write<scene::Transform>(camera).rotation = glm::angleAxis(glm::radians(kDegreesPerFrame * float(i)), glm::vec3(0, 1, 0)) * start;
      run.step();
      frames.push_back(run.indirect());
    }
    EXPECT_DOUBLE_EQ(vctOf(run).stats().tracedFraction, 1.0 / traceFrames) << "the trace is spread as asked";
    return frames;
  };
  const std::vector<render::ImageRgba> still1 = pan(1, false), still4 = pan(4, false);
  double stillDifference = 0;
  for (size_t i = 0; i < still1.back().size(); ++i)
    stillDifference = std::max(stillDifference, double(glm::length(glm::vec3(still1.back()[i] - still4.back()[i]))));
  dyngi::test::report("still view after %d frames: largest difference %.3g\n", kFrames, stillDifference);
  EXPECT_EQ(stillDifference, 0.0) << "a still view converges to the every-frame image";

  const std::vector<render::ImageRgba> every = pan(1, true), spread = pan(4, true);
  const render::ImageRgba& truth = every.back();
  dump("vct_spread_pan_every", truth, kSize, kSize);
  dump("vct_spread_pan_spread", spread.back(), kSize, kSize);
  const double rel = render::relativeMse(spread.back(), truth), relStale = render::relativeMse(every[kFrames - 4], truth);
  const double p99 = render::relativeLuminanceErrorQuantile(spread.back(), truth, 0.99);
  const double p99Stale = render::relativeLuminanceErrorQuantile(every[kFrames - 4], truth, 0.99);
  dyngi::test::report("pan, against the every-frame trace: spread over 4 frames relMSE %.5f p99 %.3f; every-frame image 3 frames old relMSE %.5f p99 %.3f\n",
              rel, p99, relStale, p99Stale);
  EXPECT_LT(rel, 0.0005);
  EXPECT_LT(p99, 0.36);
  EXPECT_LT(rel, 0.1 * relStale);
}

// Under a GI budget (Technique::spreadOneOffWork) a frame without trace history, here after the spot
// jumped, traces its quarter of the pixels as any other frame and the upsample fills the rest from them,
// instead of tracing every pixel at 4 times the cost (its rows, all of one parity, pair up over the cone
// set). Against the unbudgeted run's full trace of that frame (the same voxels): close, no holes, and far
// closer than last frame's light; 4 frames later, every pixel traced with its own cones since in both
// runs, the same image bit for bit.
TEST_F(RenderTest, VctBudgetSpreadsTheTraceOfAFrameWithoutHistory) {
  const gi::GiSettings s = vctSettings();
  ASSERT_EQ(s.vct.traceFrames, 4u);
  GiRun full(context(), s, "cornell", kSize, kSize), spread(context(), s, "cornell", kSize, kSize);
  spread.gi->technique().spreadOneOffWork(true);
  for (GiRun* run : {&full, &spread}) run->step(8);
  const render::ImageRgba before = full.indirect();
  EXPECT_EQ(render::relativeMse(spread.indirect(), before), 0.0) << "a still view: the same image once every pixel had its turn";
  for (GiRun* run : {&full, &spread}) {
    run->world.write<scene::Transform>(run->named("spot")).translation.x += 0.3f;
    run->step();
  }
  EXPECT_DOUBLE_EQ(vctOf(full).stats().tracedFraction, 1.0) << "unbudgeted, a jump traces every pixel";
  EXPECT_TRUE(full.gi->technique().lastFrameWasOneOff());
  EXPECT_DOUBLE_EQ(vctOf(spread).stats().tracedFraction, 0.25);
  EXPECT_FALSE(spread.gi->technique().lastFrameWasOneOff());
  const render::ImageRgba truth = full.indirect(), spreadImage = spread.indirect();
  dump("vct_no_history_full", truth, kSize, kSize);
  dump("vct_no_history_spread", spreadImage, kSize, kSize);
  const double rel = render::relativeMse(spreadImage, truth), relBefore = render::relativeMse(before, truth);
  const double p99 = render::relativeLuminanceErrorQuantile(spreadImage, truth, 0.99);
  const double mean = luminance(render::meanOver(truth));
  size_t holes = 0;  // lit pixels the spread frame left dark
  for (size_t i = 0; i < truth.size(); ++i)
    holes += luminance(glm::dvec3(truth[i])) > 0.1 * mean && luminance(glm::dvec3(spreadImage[i])) < 0.01 * mean;
  dyngi::test::report("spot jumped, a quarter traced: relMSE %.5f p99 %.3f against the full trace (last frame's light: relMSE %.4f), %zu holes\n", rel,
                      p99, relBefore, holes);
  EXPECT_EQ(holes, 0u);
  EXPECT_LT(rel, 0.1 * relBefore);
  for (GiRun* run : {&full, &spread}) run->step(4);
  EXPECT_EQ(render::relativeMse(spread.indirect(), full.indirect()), 0.0) << "every pixel traced with its own cones since the jump in both";
}

namespace {
std::vector<gi::VolumeLevel> readLevels(render::VulkanContext& ctx, render::Image& img) {
  std::vector<gi::VolumeLevel> levels;
  const auto& d = img.desc();
  for (uint32_t m = 0; m < d.mips; ++m) {
    gi::VolumeLevel l{std::max(d.width >> m, 1u), std::max(d.height >> m, 1u), std::max(d.depth >> m, 1u), {}};
    for (const glm::vec4& v : render::readbackImageLevel(ctx, img, m)) l.texels.push_back(v);
    levels.push_back(std::move(l));
  }
  return levels;
}

// Largest difference of two levels, relative to the level's largest value (half floats round to 1/2048).
double maxRelativeDifference(const gi::VolumeLevel& a, const gi::VolumeLevel& b) {
  double worst = 0.0, scale = 1e-6;
  for (size_t i = 0; i < a.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      scale = std::max(scale, double(std::abs(b.texels[i][c])));
      worst = std::max(worst, double(std::abs(a.texels[i][c] - b.texels[i][c])));
    }
  return worst / scale;
}
}  // namespace

namespace {
// Two runs of the Cornell box, the radiance updated every frame and spread over 4, without temporal
// blending (so that each update is a function of the light alone), stepped in lockstep.
struct SpreadPair {
  static gi::GiSettings settings(uint32_t radianceFrames) {
    gi::GiSettings s = vctSettings();
    s.vct.radianceFrames = radianceFrames;
    s.vct.temporalBlend = 0.0f;
    return s;
  }
  explicit SpreadPair(render::VulkanContext& context)
      : ctx(context), every(context, settings(1), "cornell", kSize, kSize), spread(context, settings(4), "cornell", kSize, kSize) {}
  void step(int frames = 1) {
    for (GiRun* run : {&every, &spread}) run->step(frames);
  }
  template <class Edit>
  void edit(Edit e) {
    for (GiRun* run : {&every, &spread}) e(*run);
  }
  std::vector<glm::vec4> direct(GiRun& run) { return render::readbackImageLevel(ctx, vctOf(run).directVolume(), 0); }
  // The largest relative difference over the atlas' levels.
  double atlasDifference() {
    const std::vector<gi::VolumeLevel> a = readLevels(ctx, vctOf(spread).anisotropicVolume()), b = readLevels(ctx, vctOf(every).anisotropicVolume());
    double worst = 0.0;
    for (size_t m = 0; m < b.size(); ++m) worst = std::max(worst, maxRelativeDifference(a[m], b[m]));
    return worst;
  }
  render::VulkanContext& ctx;
  GiRun every, spread;
};
bool sameRadiance(const glm::vec4& a, const glm::vec4& b) {
  return glm::length(glm::vec3(a - b)) <= 1e-3f * std::max(glm::length(glm::vec3(b)), 1e-3f) && a.a == b.a;
}
}  // namespace

// The radiance update spread over 4 frames (a GI budget's radiance_update_fraction 1/4): after a light
// moves, the first frame updates a part of the voxels; three cycles later the direct radiance and every
// atlas level equal the every-frame update's, and 4 frames more (the trace's spread) the image.
TEST_F(RenderTest, VctRadianceSpreadOverFramesReachesTheWholeUpdate) {
  SpreadPair pair(context());
  pair.step(3);
  const std::vector<glm::vec4> before = pair.direct(pair.every);
  pair.edit([](GiRun& run) { run.world.write<scene::Transform>(run.named("spot")).translation.x += 0.3f; });
  pair.step();
  EXPECT_DOUBLE_EQ(vctOf(pair.spread).stats().radianceUpdated, 0.25);
  EXPECT_FALSE(pair.spread.gi->voxels()->stats().rebuilt) << "a light moved: the SVO stands, the update is spread";
  const std::vector<glm::vec4> now = pair.direct(pair.every), partly = pair.direct(pair.spread);
  size_t changed = 0, updated = 0;
  for (size_t i = 0; i < now.size(); ++i) {
    if (sameRadiance(now[i], before[i])) continue;
    ++changed;
    updated += sameRadiance(partly[i], now[i]);
  }
  dyngi::test::report("light moved, radiance spread over 4 frames: %zu of %zu changed voxels updated in the first frame (%.2f)\n", updated, changed,
                      double(updated) / double(std::max<size_t>(changed, 1)));
  // The changed voxels lie where the spot shines and a part is a run of the leaf list, mostly one region
  // (which one varies from run to run): some of them, not all.
  ASSERT_GT(changed, 1000u);
  EXPECT_GT(double(updated) / double(changed), 0.02) << "this frame's part updated";
  EXPECT_LT(double(updated) / double(changed), 0.90) << "a part, not the whole volume";
  pair.step(15);  // three cycles of 4 frames, then the trace's 4
  const double direct = maxRelativeDifference(readLevels(context(), vctOf(pair.spread).directVolume()).front(),
                                              readLevels(context(), vctOf(pair.every).directVolume()).front());
  const double atlas = pair.atlasDifference(), image = render::relativeMse(pair.spread.indirect(), pair.every.indirect());
  dyngi::test::report("three cycles and a trace spread later: direct radiance differs by %.2g, the atlas by %.2g, the indirect image relMSE %.2g\n",
                      direct, atlas, image);
  EXPECT_LE(direct, 1e-3);
  EXPECT_LE(atlas, 1e-3);
  EXPECT_LE(image, 1e-6);
}

// Spread over 4 frames, a frame whose SVO build changed voxels (a box moved) still updates the boxes it
// changed: the box's new voxels carry their light at once, as the every-frame update's do; three cycles
// (and the trace's spread) later everything equals it.
TEST_F(RenderTest, VctRadianceSpreadUpdatesAMovedObjectAtOnce) {
  SpreadPair pair(context());
  pair.step(3);
  const std::vector<glm::vec4> before = pair.direct(pair.every);
  pair.edit([](GiRun& run) { run.world.write<scene::Transform>(run.named("short_box")).translation.z += 0.25f; });
  pair.step();
  EXPECT_TRUE(pair.spread.gi->voxels()->stats().rebuilt);
  EXPECT_DOUBLE_EQ(vctOf(pair.spread).stats().radianceUpdated, 0.25) << "the update stays spread on a rebuilt frame";
  const std::vector<glm::vec4> now = pair.direct(pair.every), partly = pair.direct(pair.spread);
  size_t filled = 0, lit = 0;
  for (size_t i = 0; i < now.size(); ++i) {
    if (!(before[i].a == 0.0f && now[i].a > 0.0f)) continue;  // a voxel the box moved into
    ++filled;
    lit += sameRadiance(partly[i], now[i]);
  }
  dyngi::test::report("box moved, radiance spread over 4 frames: %zu of %zu voxels it moved into updated at once\n", lit, filled);
  ASSERT_GT(filled, 100u);
  EXPECT_EQ(lit, filled);
  pair.step(15);  // three cycles of 4 frames, then the trace's 4
  const double atlas = pair.atlasDifference(), image = render::relativeMse(pair.spread.indirect(), pair.every.indirect());
  dyngi::test::report("three cycles and a trace spread later: the atlas differs by %.2g, the image relMSE %.2g\n", atlas, image);
  EXPECT_LE(atlas, 1e-3);
  EXPECT_LE(image, 1e-6);
}

TEST_F(RenderTest, VctMipChainEqualsCpuFilters) {
  for (int mode : {0, 1, 2}) {  // isotropic mean, isotropic opaque axis, anisotropic
    const bool aniso = mode == 2;
    gi::GiSettings s = vctSettings();
    s.voxels.resolution = 64;
    s.vct.anisotropic = aniso;
    s.vct.opaqueAxisMips = mode == 1;
    GiRun run(context(), s, "cornell", 64, 64);
    run.step(2);
    gi::VoxelConeTracing& vct = vctOf(run);
    const std::vector<gi::VolumeLevel> radiance = readLevels(context(), vct.radianceVolume());
    size_t occupied = 0;
    for (const glm::vec4& t : radiance[0].texels) occupied += t.a > 0.5f;
    EXPECT_GT(occupied, 1000u) << "the volume holds the box's voxels";
    if (!aniso) {
      for (size_t m = 1; m < radiance.size(); ++m) {
        const gi::VolumeLevel cpu = mode == 1 ? gi::vctOpaqueAxisDownsample(radiance[m - 1]) : gi::vctBoxDownsample(radiance[m - 1]);
        EXPECT_LT(maxRelativeDifference(radiance[m], cpu), 2e-3) << "mode " << mode << ", isotropic level " << m;
      }
      continue;
    }
    const std::vector<gi::VolumeLevel> atlas = readLevels(context(), vct.anisotropicVolume());
    const gi::VolumeLevel seen = readLevels(context(), vct.directVolume()).at(0);  // its alpha: which cones see a voxel
    size_t hiddenBacks = 0;  // one-sided voxels, whose back the first atlas level shows black
    for (size_t i = 0; i < seen.texels.size(); ++i)
      hiddenBacks += radiance[0].texels[i].a > 0.5f && !gi::vctSeenBothSides(seen.texels[i].a);
    EXPECT_GT(hiddenBacks, occupied / 2) << "most of the Cornell box's voxels are one-sided";
    ASSERT_EQ(atlas.size(), radiance.size() - 1);
    for (size_t m = 0; m < atlas.size(); ++m) {
      const uint32_t slab = atlas[m].h;
      const gi::VolumeLevel cpu =
          m == 0 ? gi::vctAnisoDownsample(radiance[0], 0, slab, &seen) : gi::vctAnisoDownsample(atlas[m - 1], 2 * slab, slab);
      EXPECT_LT(maxRelativeDifference(atlas[m], cpu), 2e-3) << "anisotropic level " << m;
    }
    // The atlas is written at the SVO's occupied nodes only: after a box moves, the texels it left must
    // be empty again, as the CPU filters of the new level 0 say.
    run.world.write<scene::Transform>(run.named("tall_box")).translation.x += 0.4f;
    run.step(1);
    const std::vector<gi::VolumeLevel> movedRadiance = readLevels(context(), vct.radianceVolume());
    const std::vector<gi::VolumeLevel> movedAtlas = readLevels(context(), vct.anisotropicVolume());
    const gi::VolumeLevel movedSeen = readLevels(context(), vct.directVolume()).at(0);
    for (size_t m = 0; m < movedAtlas.size(); ++m) {
      const uint32_t slab = movedAtlas[m].h;
      const gi::VolumeLevel cpu = m == 0 ? gi::vctAnisoDownsample(movedRadiance[0], 0, slab, &movedSeen)
                                         : gi::vctAnisoDownsample(movedAtlas[m - 1], 2 * slab, slab);
      EXPECT_LT(maxRelativeDifference(movedAtlas[m], cpu), 2e-3) << "anisotropic level " << m << " after the tall box moved";
    }
  }
}

// Both anisotropic and isotropic, at the unit step (its pipelines skip a pow() a step), a half step and
// the default (1.15 footprints, folded into the slab fractions).
TEST_F(RenderTest, VctConeMarchEqualsCpuTwin) {
  for (const auto& [aniso, step, narrowing] :
       {std::tuple{false, 1.0f, 0.0f}, {true, 1.0f, 0.0f}, {true, 0.5f, 0.0f}, {true, 1.15f, 0.0f}, {false, 1.15f, 0.0f}, {true, 1.15f, 0.75f}}) {
    gi::GiSettings s = vctSettings();
    s.voxels.resolution = 64;
    s.vct.anisotropic = aniso;
    s.vct.coneStep = step;
    s.vct.farNarrowing = narrowing;
    GiRun run(context(), s, "cornell", 64, 64);
    run.step(2);
    gi::VoxelConeTracing& vct = vctOf(run);
    const std::vector<gi::VolumeLevel> radiance = readLevels(context(), vct.radianceVolume());
    std::vector<gi::VolumeLevel> atlas;
    if (aniso) atlas = readLevels(context(), vct.anisotropicVolume());
    gi::VctConeParams p;
    p.res = 64;
    p.maxDistance = vct.settings().maxDistance * 64.0f;
    p.aoDistance = vct.settings().aoDistance * 64.0f;
    p.coneOffset = vct.settings().coneOffset;
    p.coneStep = vct.settings().coneStep;
    p.farNarrowing = vct.settings().farNarrowing;
    p.anisotropic = aniso;
    // Rays from inside the box in every direction, narrow and wide cones.
    std::vector<std::pair<glm::vec3, glm::vec3>> rays;
    uint32_t state = 12345;
    auto rnd = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    for (int i = 0; i < 96; ++i) {
      const glm::vec3 o(12.0f + 40.0f * rnd(), 8.0f + 40.0f * rnd(), 12.0f + 40.0f * rnd());
      glm::vec3 d(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f);
      rays.push_back({o, glm::normalize(d + glm::vec3(1e-3f))});
    }
    for (float tanHalf : {0.1f, 0.6f}) {
      const std::vector<glm::vec4> gpu = vct.probeCones(rays, tanHalf);
      double worst = 0.0, sum = 0.0, lit = 0.0;
      for (size_t i = 0; i < rays.size(); ++i) {
        const glm::vec4 cpu = gi::vctConeCpu(radiance, atlas, p, rays[i].first, rays[i].second, tanHalf);
        const double e = std::max(double(std::abs(cpu.a - gpu[i].a)), double(glm::length(glm::vec3(cpu) - glm::vec3(gpu[i]))) /
                                                                          std::max(double(glm::length(glm::vec3(cpu))), 0.02));
        worst = std::max(worst, e);
        sum += e;
        lit += glm::length(glm::vec3(cpu)) > 0.01 ? 1.0 : 0.0;
      }
      dyngi::test::report("anisotropic %d step %.2f far narrowing %.2f tan %.1f: cone march GPU vs CPU twin: worst %.4f, mean %.5f over %zu rays (%.0f lit)\n",
                  int(aniso), double(step), double(narrowing), double(tanHalf), worst, sum / double(rays.size()), rays.size(), lit);
      EXPECT_GT(lit, 20.0);
      EXPECT_LT(sum / double(rays.size()), 0.01);
      EXPECT_LT(worst, 0.08);
    }
  }
}

// Radiance injection against the rasterized direct light: every voxel under a directly lit pixel holds
// the radiance that pixel's surface reflects (the same lights, shadow maps and Lambert model), within the
// spread a voxel's averaging gives at shadow edges.
TEST_F(RenderTest, VctInjectedRadianceEqualsTheDirectLight) {
  GiRun run(context(), vctSettings(), "cornell", kSize, kSize);
  run.step(2);
  Frame f = run.readFrame();
  const render::ImageRgba direct = run.pathTraced(4, 0);  // direct light only: exact, no noise
  const std::vector<gi::VolumeLevel> radiance = readLevels(context(), vctOf(run).radianceVolume());
  const gi::VoxelVolume vol = run.gi->voxels()->volume();
  std::vector<double> ratios;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const glm::vec4 p = f.at(f.position, x, y);
      const double d = lum(glm::dvec3(direct[size_t(y) * kSize + x]));
      if (p.w < 0.5f || d < 0.05) continue;
      const glm::vec3 n = glm::vec3(f.at(f.normal, x, y));
      const glm::ivec3 c(glm::floor(vol.toVoxel(glm::vec3(p)) - 0.01f * n));
      const glm::vec4 v = radiance[0].at(c.x, c.y, c.z);
      ASSERT_GT(v.a, 0.5f) << "the voxel of a visible surface is occupied";
      ratios.push_back(lum(glm::dvec3(v)) / d);
    }
  ASSERT_GT(ratios.size(), 1000u);
  std::sort(ratios.begin(), ratios.end());
  const double median = ratios[ratios.size() / 2];
  size_t within = 0;
  for (double r : ratios) within += std::abs(r - 1.0) < 0.25;
  dyngi::test::report("voxel radiance / direct radiance over %zu lit pixels: median %.3f, %.1f%% within 25%%\n", ratios.size(), median,
              100.0 * double(within) / double(ratios.size()));
  EXPECT_NEAR(median, 1.0, 0.05);
  EXPECT_GT(double(within) / double(ratios.size()), 0.9);
}

namespace {
// Room B's mean luminance (final image) over the pixels that show room B (beyond the shared wall).
double roomBMean(render::VulkanContext& ctx, const gi::GiSettings& s, const std::string& scene) {
  GiRun run(ctx, s, scene, 64, 64);
  run.step(3);
  const Frame f = run.readFrame();
  std::vector<uint8_t> mask(f.position.size(), 0);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = f.position[i].w != 0.0f && f.position[i].x > 0.0f;
  return lum(render::meanOver(f.hdr, &mask));
}
}  // namespace

// Light leaking through the two-room scene's wall (0.05 m: 1.5 voxels at 128^3, 2.9 at 256^3), room B
// (no light) closed against room B with a doorway, for the three mip chains: isotropic mean, isotropic
// with each texel's most opaque axis, anisotropic (six directions). At 128^3; DYNGI_VCT_LEAK_256=1 adds
// 256^3 (a minute more under the sanitizers; docs/QUALITY.md has its figures).
TEST_F(RenderTest, VctLeakThroughAThinWallPerMipChain) {
  const char* names[] = {"isotropic mean", "isotropic opaque axis", "anisotropic"};
  std::map<std::pair<uint32_t, int>, double> leak;
  std::vector<uint32_t> resolutions = {128u};
  if (std::getenv("DYNGI_VCT_LEAK_256")) resolutions.push_back(256u);
  for (uint32_t res : resolutions)
    for (int mode : {0, 1, 2}) {
      gi::GiSettings s = vctSettings();
      s.voxels.resolution = res;
      s.vct.anisotropic = mode == 2;
      s.vct.opaqueAxisMips = mode == 1;
      const double closed = roomBMean(context(), s, "two-rooms"), door = roomBMean(context(), s, "two-rooms-door");
      ASSERT_GT(door, 0.0);
      leak[{res, mode}] = closed / door;
      dyngi::test::report("vct-leak| %u^3 | %s | room B closed %.5f | with a doorway %.5f | leak %.1f%%\n", res, names[mode], closed, door,
                  100.0 * closed / door);
    }
  // The mean halves a thin wall's opacity at every level: light passes. The opaque axis keeps the wall
  // opaque for every direction: under the goal of 5 percent. The anisotropic atlas keeps it opaque along
  // its normal, but room A's lit floor runs under the wall and a texel straddling the wall shows it to a
  // room-B cone travelling down and towards the wall through the -y slab. The far samples' narrowing
  // (VctOptions::farNarrowing 0.75, with 12 cones, 6 a pixel) straddles the wall less: 4.9 percent at
  // 128^3, 5.4 at 256^3; without it, with 6 wide cones, 8.3 and 10.5 percent.
  gi::GiSettings wide = vctSettings();
  wide.vct.farNarrowing = 0.0f;
  wide.vct.diffuseCones = 6;
  wide.vct.coneInterleave = 1;
  const double wideClosed = roomBMean(context(), wide, "two-rooms"), wideDoor = roomBMean(context(), wide, "two-rooms-door");
  dyngi::test::report("vct-leak| 128^3 | anisotropic, no far narrowing, 6 cones a pixel | room B closed %.5f | with a doorway %.5f | leak %.1f%%\n",
              wideClosed, wideDoor, 100.0 * wideClosed / wideDoor);
  for (uint32_t res : resolutions) {
    const double mean = leak[{res, 0}], opaqueAxis = leak[{res, 1}], aniso = leak[{res, 2}];
    EXPECT_LT(opaqueAxis, 0.05) << res;
    EXPECT_LT(opaqueAxis, mean) << res;
    EXPECT_LT(aniso, mean) << res;
    EXPECT_LT(aniso, res == 128u ? 0.05 : 0.07) << res;
  }
  const double defaultLeak = leak[{128u, 2}];
  EXPECT_LT(defaultLeak, 0.7 * wideClosed / wideDoor) << "the far narrowing is what keeps the leak under the goal";
}

// An emissive quad as the only light (../shared/scenes/CornellBox.glb): its light reaches the floor and
// the walls through the cones, within 30 percent of the path tracer per surface. The voxels take the
// panel's light as they take a light's (VctOptions::emitterSamples), so the cones bring one bounce of
// it: the path tracer's 2 bounces.
TEST_F(RenderTest, VctEmissiveOnlySceneLightsTheRoom) {
  DYNGI_SHARED_SCENE_OR_SKIP(path, "CornellBox.glb");
  constexpr uint32_t kEmissiveSize = 96;
  // The path tracer is Lambert only; this scene's materials have roughness 0.5, whose specular
  // reflection (4 percent of the bright panel) would outweigh the dark red wall's diffuse light.
  gi::GiSettings s = vctSettings();
  s.vct.specular = false;
  GiRun run(
      context(), s, [&](ecs::World& w, scene::AssetStore& a) { ASSERT_EQ(scene::importGltf(path, w, a), ""); }, kEmissiveSize,
      kEmissiveSize);
  run.step(3);
  Frame f = run.readFrame();
  const render::ImageRgba ref = run.pathTraced(4096, 2);
  dump("vct_emissive", f.hdr, kEmissiveSize, kEmissiveSize);
  dump("vct_emissive_path", ref, kEmissiveSize, kEmissiveSize);
  // Surfaces by their G-buffer normal. The ceiling is left out: it is in the emitter's plane and sees
  // nothing of it (the path tracer's 0.0007), where the voxels' isotropic radiance gives it 0.01.
  const std::pair<const char*, glm::vec3> surfaces[] = {
      {"floor", {0, 1, 0}}, {"left wall", {1, 0, 0}}, {"right wall", {-1, 0, 0}}, {"back wall", {0, 0, 1}}};
  size_t checked = 0;
  for (const auto& [name, normal] : surfaces) {
    size_t n = 0;
    const std::vector<uint8_t> mask = surfaceFacing(f, ref, normal, n);
    if (n < 100) continue;
    const double a = lum(render::meanOver(f.hdr, &mask)), b = lum(render::meanOver(ref, &mask));
    dyngi::test::report("emissive-only %-11s vct %.4f  path %.4f  ratio %.3f  (%zu px)\n", name, a, b, a / b, n);
    // The goal: 30 percent. The floor, 125 voxels under the panel, is the tight one (0.83; the walls 1.06
    // to 1.12): with a cone reach of one volume side its cones stop short of the ceiling.
    EXPECT_NEAR(a / b, 1.0, 0.30) << name;
    ++checked;
  }
  EXPECT_GE(checked, 4u);
}


namespace {
// The camera the scenes below render from.
void addActiveCamera(ecs::World& w, const scene::Transform& t, float yfovDegrees) {
  const ecs::Entity cam = w.create();
  w.add(cam, t);
  w.add(cam, scene::WorldTransform{t.matrix()});
  w.add(cam, scene::Camera{.yfov = glm::radians(yfovDegrees), .znear = 0.05f, .zfar = 50.0f});
  w.add(cam, scene::ActiveCamera{});
}

// A 0.5 m box on a 6 x 6 m floor under a sun, seen from above at 45 degrees: the ambient occlusion scene.
void boxOnAPlane(ecs::World& w, scene::AssetStore& a) {
  sample::addSceneMesh(w, a, scene::makeQuad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}), glm::vec3(0.75f), {}, false, "floor");
  scene::Transform box;
  box.translation = {0.0f, 0.25f, 0.0f};
  sample::addSceneMesh(w, a, scene::makeBox({0.25f, 0.25f, 0.25f}), glm::vec3(0.75f), box, false, "box");
  const ecs::Entity sun = w.create();
  scene::Transform st;
  st.rotation = glm::angleAxis(glm::radians(-70.0f), glm::vec3(1, 0, 0));
  w.add(sun, st);
  w.add(sun, scene::WorldTransform{st.matrix()});
  scene::Light light;
  light.type = scene::LightType::Directional;
  light.intensity = 2.0f;
  w.add(sun, light);
  scene::Transform ct;
  ct.translation = {0.0f, 2.2f, 2.2f};
  ct.rotation = glm::angleAxis(glm::radians(-45.0f), glm::vec3(1, 0, 0));
  addActiveCamera(w, ct, 50.0f);
}
}  // namespace

// Ambient occlusion: the floor beside the box is darker than the open floor, and the darkening falls
// with the distance from the box.
TEST_F(RenderTest, VctAmbientOcclusionFallsWithDistanceFromABox) {
  GiRun run(context(), vctSettings(), boxOnAPlane, kSize, kSize);
  run.step(2);
  const Frame f = run.readFrame();
  const render::ImageRgba indirect = run.indirect();  // AO in alpha
  // Floor pixels beside the box's +x face (x = 0.25), |z| < 0.15, in bands of distance from the face.
  const double bands[][2] = {{0.0, 0.08}, {0.1, 0.25}, {0.3, 0.6}, {1.0, 1.6}};
  std::vector<double> ao;
  for (const auto& band : bands) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < f.position.size(); ++i) {
      const glm::vec4 p = f.position[i];
      const double d = double(p.x) - 0.25;
      if (p.w < 0.5f || std::abs(p.y) > 1e-3f || f.normal[i].y < 0.99f || std::abs(p.z) > 0.15f || d < band[0] || d > band[1]) continue;
      sum += double(indirect[i].a);
      ++n;
    }
    ASSERT_GT(n, 3) << "floor pixels " << band[0] << ".." << band[1] << " m from the box";
    ao.push_back(sum / n);
    dyngi::test::report("AO %.2f..%.2f m from the box: %.3f (%d px)\n", band[0], band[1], ao.back(), n);
  }
  for (size_t b = 1; b < ao.size(); ++b) EXPECT_GT(ao[b], ao[b - 1]) << "band " << b;
  EXPECT_LT(ao.front(), 0.85 * ao.back()) << "the box darkens the floor beside it";
  EXPECT_GT(ao.back(), 0.9) << "the open floor is unoccluded";
}

// The specular cone: a glossy floor (roughness 0.1) shows the red wall's reflection (its pixels near the
// wall are redder than a rough floor's), and the reflection blurs as the roughness grows.
TEST_F(RenderTest, VctSpecularReflectsTheRedWallAndBlursWithRoughness) {
  std::map<float, double> redness, reflectionRedness, sharpness;
  for (float roughness : {0.1f, 0.4f, 1.0f}) {
    gi::GiSettings s = vctSettings();
    s.vct.traceScale = 1;  // the reflection's own sharpness, not the upsample's
    GiRun run(context(), s, "cornell", kSize, kSize);
    run.world.write<scene::Material>(run.named("floor")).roughness = roughness;
    run.step(2);
    const Frame f = run.readFrame();
    // Under VctOptions::specularConeBelow a cone is marched; at roughness 1 every draw is rougher than
    // that: no cone anywhere, and the lighting takes the diffuse light (E / pi) as every pixel's specular
    // light (SpecularSource::Indirect; VctSpecularFromTheIndirectImageMatchesTheSpecularImage).
    const bool rough = roughness >= s.vct.specularConeBelow;
    EXPECT_EQ(vctOf(run).stats().specularCones, !rough) << roughness;
    const render::ImageRgba specular = run.renderer->readback(rough ? render::TargetId::Indirect : render::TargetId::Specular);
    dump("vct_specular_roughness_" + std::to_string(int(roughness * 10)), specular, kSize, kSize);
    std::vector<uint8_t> nearRed(f.hdr.size(), 0);
    for (size_t i = 0; i < nearRed.size(); ++i)
      nearRed[i] = f.position[i].w > 0.5f && std::abs(f.position[i].y) < 1e-3f && f.position[i].x < -0.6f;
    const glm::dvec3 c = render::meanOver(f.hdr, &nearRed), r = render::meanOver(specular, &nearRed);
    redness[roughness] = c.r / c.g;
    reflectionRedness[roughness] = r.r / r.g;
    // Sharpness: the specular image's mean absolute step between horizontal neighbours on the floor,
    // relative to its mean, over the floor's interior (pixels at least 3 from anything else): where the
    // floor meets a box or a wall its reflection steps by the contact, not by how sharp it is. A rough
    // floor's reflection is dim (at roughness 1 the boxes' and walls' bases are most of what it shows
    // near them), so those few steps would outweigh the rest.
    const auto isFloor = [&](int x, int y) {
      if (x < 0 || y < 0 || x >= int(kSize) || y >= int(kSize)) return false;
      const glm::vec4& p = f.position[size_t(y) * kSize + size_t(x)];
      return p.w > 0.5f && std::abs(p.y) < 1e-3f;
    };
    const auto interior = [&](int x, int y) {
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx)
          if (!isFloor(x + dx, y + dy)) return false;
      return true;
    };
    double steps = 0, mean = 0;
    int n = 0;
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x + 1 < kSize; ++x) {
        if (!interior(int(x), int(y)) || !interior(int(x) + 1, int(y))) continue;
        const size_t i = size_t(y) * kSize + x;
        steps += std::abs(lum(glm::dvec3(specular[i + 1])) - lum(glm::dvec3(specular[i])));
        mean += lum(glm::dvec3(specular[i]));
        ++n;
      }
    ASSERT_GT(n, 500);
    sharpness[roughness] = steps / std::max(mean, 1e-9);
    dyngi::test::report("roughness %.1f: floor near the red wall r/g %.3f (its reflection alone %.3f), reflection sharpness %.4f\n",
                double(roughness), redness[roughness], reflectionRedness[roughness], sharpness[roughness]);
  }
  // A white dielectric floor reflects 4 percent at normal incidence: the final image's tint is small but
  // there; the reflection itself is markedly redder.
  EXPECT_GT(redness[0.1f], 1.01 * redness[1.0f]) << "the glossy floor mirrors the red wall";
  EXPECT_GT(reflectionRedness[0.1f], 1.1 * reflectionRedness[1.0f]);
  EXPECT_GT(sharpness[0.1f], sharpness[0.4f]);
  EXPECT_GT(sharpness[0.4f], sharpness[1.0f]);
}

// A rough pixel's specular light is its diffuse light: with no draw smoother than specularConeBelow the
// lighting reads it from the indirect image (SpecularSource::Indirect), the same image as when the
// upsample writes it to the specular image, which a roughness texture on the floor brings back (a
// missing one: white, so every pixel stays at roughness 1; the trace then holds the cone's code).
TEST_F(RenderTest, VctSpecularFromTheIndirectImageMatchesTheSpecularImage) {
  GiRun plain(context(), vctSettings(), "cornell", kSize, kSize);
  GiRun textured(context(), vctSettings(), "cornell", kSize, kSize);
  textured.world.write<scene::Material>(textured.named("floor")).metallicRoughnessTexture = scene::TextureId(4242);
  plain.step(3);
  textured.step(3);
  EXPECT_FALSE(vctOf(plain).stats().specularCones);
  EXPECT_TRUE(vctOf(textured).stats().specularCones);
  const Frame a = plain.readFrame(), b = textured.readFrame();
  const render::ImageRgba specular = textured.renderer->readback(render::TargetId::Specular),
                          indirect = textured.renderer->readback(render::TargetId::Indirect);
  double worstSpecular = 0, worstImage = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.hdr.size(); ++i) {
    if (a.position[i].w < 0.5f) continue;
    ++n;
    const glm::vec3 d(indirect[i]);
    worstSpecular = std::max(worstSpecular, double(glm::length(glm::vec3(specular[i]) - d) / std::max(glm::length(d), 1e-3f)));
    const glm::vec3 x(a.hdr[i]), y(b.hdr[i]);
    worstImage = std::max(worstImage, double(glm::length(x - y) / std::max(glm::length(y), 1e-3f)));
  }
  ASSERT_GT(n, 1000u);
  dyngi::test::report("specular image against the diffuse light: worst %.2e; final images: worst %.2e\n", worstSpecular, worstImage);
  EXPECT_LT(worstSpecular, 1e-3) << "the specular image holds each pixel's diffuse light";
  EXPECT_LT(worstImage, 1e-4) << "either way the lighting adds the same specular light";
}

// Dynamic scenes: a moved light is re-injected without re-voxelizing; a moved box leaves empty voxels
// behind; a light switched off takes the indirect light with it within a frame.
TEST_F(RenderTest, VctFollowsMovedLightsAndObjectsAndSwitchedLights) {
  GiRun run(context(), vctSettings(), "cornell", kSize, kSize);
  run.step(3);
  gi::VoxelConeTracing& vct = vctOf(run);
  const gi::VoxelVolume vol = run.gi->voxels()->volume();
  const std::vector<glm::vec4> before = render::readbackImageLevel(context(), vct.directVolume(), 0);
  run.world.write<scene::Transform>(run.named("spot")).translation.x += 0.3f;
  run.step();
  EXPECT_EQ(run.gi->voxels()->stats().entitiesVoxelized, 0u) << "a light moved: nothing to re-voxelize";
  EXPECT_FALSE(run.gi->voxels()->stats().rebuilt);
  EXPECT_TRUE(vct.stats().injected);
  const std::vector<glm::vec4> after = render::readbackImageLevel(context(), vct.directVolume(), 0);
  double change = 0, total = 0;
  for (size_t i = 0; i < after.size(); ++i) change += std::abs(double(after[i].g - before[i].g)), total += double(before[i].g);
  dyngi::test::report("light moved 0.3 m: injected radiance changed by %.1f%% (relative L1)\n", 100 * change / total);
  EXPECT_GT(change / total, 0.05);

  // The tall box's top face (y = 1.2 m) moves away: its voxels are empty the next frame.
  const glm::ivec3 top(glm::floor(vol.toVoxel({-0.35f, 1.2f, -0.35f}) - glm::vec3(0, 0.01f, 0)));
  auto occupiedAround = [&](const glm::ivec3& c, render::Image& volume) {
    const gi::VolumeLevel l0 = readLevels(context(), volume).front();
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dx = -1; dx <= 1; ++dx) n += l0.at(c.x + dx, c.y, c.z + dz).a > 0.5f;
    return n;
  };
  EXPECT_GE(occupiedAround(top, vct.radianceVolume()), 5) << "the box's top is voxelized";
  EXPECT_GE(occupiedAround(top, vct.directVolume()), 5);
  run.world.write<scene::Transform>(run.named("tall_box")).translation = {0.5f, 0.6f, -0.5f};
  run.step();
  EXPECT_EQ(occupiedAround(top, vct.radianceVolume()), 0) << "the voxels the box left are empty";
  // The direct radiance (blended in place with last frame's) and in the frame after.
  for (int frame = 0; frame < 2; ++frame) {
    EXPECT_EQ(occupiedAround(top, vct.directVolume()), 0) << "frame " << frame << " after the move: the direct radiance the box left";
    run.step();
  }

  // The spot switched off: no light is left to bounce (temporal blending keeps no trail of it).
  run.step(2);
  const double lit = lum(render::meanOver(run.indirect()));
  ASSERT_GT(lit, 0.0);
  run.world.write<scene::Light>(run.named("spot")).enabled = false;
  run.step();
  const double off = lum(render::meanOver(run.indirect()));
  dyngi::test::report("spot switched off: indirect light %.5f -> %.5f one frame later (%.2f%%)\n", lit, off, 100 * off / lit);
  EXPECT_LT(off, 0.01 * lit) << "within one frame";
}

// What emptied is zeroed: after both boxes move for a few frames (the voxels each leaves found by the
// SVO's occupancy within its old bounds, vct_clear_stale.comp), the texels that hold anything in
// radiance level 0, the direct image, the carried bounce light and every level of the atlas are exactly
// those of a volume built afresh with the boxes where they ended.
TEST_F(RenderTest, VctVolumesAfterMotionHoldExactlyTheVoxelsOfAFreshBuild) {
  auto place = [](GiRun& run, int step) {
    scene::Transform& tall = run.world.write<scene::Transform>(run.named("tall_box"));
    tall.translation = {-0.35f + 0.03f * float(step), 0.6f, -0.35f};
    tall.rotation = glm::angleAxis(glm::radians(17.0f + 4.0f * float(step)), glm::vec3(0, 1, 0));
    run.world.write<scene::Transform>(run.named("short_box")).translation = {0.35f, 0.3f, 0.3f - 0.02f * float(step)};
  };
  gi::GiSettings settings = vctSettings();
  // The carried bounce light: the fresh run's first frame updates every voxel's, the moving run each
  // frame a quarter of them and every voxel in the boxes the build changed.
  settings.vct.bounceFrames = 4;
  GiRun moving(context(), settings, "cornell", kSize, kSize);
  moving.step(2);
  constexpr int kSteps = 6;
  for (int k = 1; k <= kSteps; ++k) {
    place(moving, k);
    moving.step();
  }
  GiRun fresh(context(), settings, "cornell", kSize, kSize);
  place(fresh, kSteps);
  fresh.step(2);
  auto held = [](const glm::vec4& v) { return v != glm::vec4(0.0f); };
  auto compare = [&](const char* name, render::Image& a, render::Image& b) {
    const std::vector<gi::VolumeLevel> la = readLevels(context(), a), lb = readLevels(context(), b);
    ASSERT_EQ(la.size(), lb.size());
    const size_t levels = (&a == &vctOf(moving).radianceVolume()) ? 1 : la.size();  // the isotropic chain past 0 is not kept
    for (size_t m = 0; m < levels; ++m) {
      size_t both = 0, onlyMoving = 0, onlyFresh = 0;
      for (size_t i = 0; i < la[m].texels.size(); ++i) {
        const bool x = held(la[m].texels[i]), y = held(lb[m].texels[i]);
        both += x && y, onlyMoving += x && !y, onlyFresh += !x && y;
      }
      dyngi::test::report("%s level %zu: %zu texels hold something in both, %zu only after the motion, %zu only fresh\n", name, m, both, onlyMoving,
                  onlyFresh);
      EXPECT_GT(both, 0u) << name << " level " << m;
      EXPECT_EQ(onlyMoving, 0u) << name << " level " << m << ": texels the boxes left still hold something";
      EXPECT_EQ(onlyFresh, 0u) << name << " level " << m;
    }
  };
  compare("radiance", vctOf(moving).radianceVolume(), vctOf(fresh).radianceVolume());
  compare("direct", vctOf(moving).directVolume(), vctOf(fresh).directVolume());
  compare("atlas", vctOf(moving).anisotropicVolume(), vctOf(fresh).anisotropicVolume());
  compare("carried", vctOf(moving).carriedVolume(), vctOf(fresh).carriedVolume());
}

// An emissive change re-injects: the tall box made emissive in a scene with no emitter glows in the
// direct radiance the same frame (the leaf attributes then sum emission again: VoxelScene::fragmentsEmit),
// and lights the room's indirect light; switched back, both return to what they were.
TEST_F(RenderTest, VctEmissiveChangeReinjectsTheSameFrame) {
  GiRun run(context(), vctSettings(), "cornell", kSize, kSize);
  run.step(3);
  gi::VoxelConeTracing& vct = vctOf(run);
  const gi::VoxelVolume vol = run.gi->voxels()->volume();
  ASSERT_FALSE(run.gi->voxels()->fragmentsEmit());
  // The tall box's top face (y = 1.2 m), seen from above: the spot does not reach it at full strength.
  const glm::ivec3 top(glm::floor(vol.toVoxel({-0.35f, 1.2f, -0.35f}) - glm::vec3(0, 0.01f, 0)));
  auto topRadiance = [&] {
    const gi::VolumeLevel l0 = readLevels(context(), vct.directVolume()).front();
    double sum = 0.0;
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dx = -1; dx <= 1; ++dx)
        if (const glm::vec4 t = l0.at(top.x + dx, top.y, top.z + dz); t.a > 0.5f) sum += lum(glm::dvec3(glm::vec3(t))), ++n;
    return n > 0 ? sum / n : -1.0;
  };
  const double before = topRadiance(), indirectBefore = lum(render::meanOver(run.indirect()));
  ASSERT_GE(before, 0.0) << "the box's top is voxelized";
  const glm::vec3 glow(4.0f);
  run.world.write<scene::Material>(run.named("tall_box")).emissive = glow;
  run.step();
  EXPECT_TRUE(run.gi->voxels()->fragmentsEmit());
  const double glowing = topRadiance(), indirectGlowing = lum(render::meanOver(run.indirect()));
  dyngi::test::report("tall box made emissive (4): its top's direct radiance %.3f -> %.3f the same frame; indirect light %.5f -> %.5f\n", before,
              glowing, indirectBefore, indirectGlowing);
  EXPECT_NEAR(glowing - before, lum(glm::dvec3(glow)), 0.1 * lum(glm::dvec3(glow))) << "its emission, taken at once (no blending)";
  EXPECT_GT(indirectGlowing, 1.5 * indirectBefore) << "the glowing box lights the room";
  run.world.write<scene::Material>(run.named("tall_box")).emissive = glm::vec3(0.0f);
  run.step();
  EXPECT_FALSE(run.gi->voxels()->fragmentsEmit());
  const double after = topRadiance();
  dyngi::test::report("and back: %.3f\n", after);
  EXPECT_NEAR(after, before, 0.05 * lum(glm::dvec3(glow)));
}

// Temporal voxel blending: a light flickering by +-10 percent a frame (a candle, a damaged lamp) makes
// the indirect light flicker with it; blending each voxel's radiance with its last smooths that, while a
// change larger than temporalResponse (a light switched off) is taken at once. Voxels an object enters or
// leaves are not blended (their opacity pops): a moving object's indirect light is as steady with the
// blend as without (1.6 percent second difference a frame under a box moving 1 cm a frame, measured here).
TEST_F(RenderTest, VctTemporalBlendingCutsFlickerWithoutLag) {
  std::map<float, double> flicker;
  for (float blend : {0.0f, 0.5f}) {
    gi::GiSettings s = vctSettings();
    s.vct.temporalBlend = blend;
    // The voxels' blend alone: a trace spread over frames would trace each pixel on frames of one parity
    // only, so each would see one of the two light levels and the flicker would not reach the screen.
    s.vct.traceFrames = 1;
    GiRun run(context(), s, "cornell", kSize, kSize);
    const float intensity = run.world.get<scene::Light>(run.named("spot")).intensity;
    run.step(3);
    std::vector<render::ImageRgba> frames;
    for (int i = 0; i < 12; ++i) {
      run.world.write<scene::Light>(run.named("spot")).intensity = intensity * (i % 2 ? 1.1f : 0.9f);
      run.step();
      frames.push_back(run.indirect());
    }
    double change = 0, mean = 0;
    for (size_t t = 1; t < frames.size(); ++t)
      for (size_t i = 0; i < frames[t].size(); ++i) {
        change += std::abs(lum(glm::dvec3(frames[t][i])) - lum(glm::dvec3(frames[t - 1][i])));
        mean += lum(glm::dvec3(frames[t][i]));
      }
    flicker[blend] = change / mean;
    dyngi::test::report("temporal blend %.1f: indirect light's change a frame under a +-10%% flickering light %.2f%%\n", double(blend),
                100 * flicker[blend]);
    if (blend > 0.0f) {
      run.world.write<scene::Light>(run.named("spot")).enabled = false;
      run.step();
      EXPECT_LT(lum(render::meanOver(run.indirect())), 0.01 * lum(render::meanOver(frames.back()))) << "no lag after a switch";
    }
  }
  EXPECT_GT(flicker[0.0f], 0.1) << "the light's flicker shows in the indirect light";
  EXPECT_LT(flicker[0.5f], 0.5 * flicker[0.0f]);
}

// Extra bounces: two bounces bring the image closer to the path tracer's two bounces than one does.
TEST_F(RenderTest, VctSecondBounceApproachesThePathTracer) {
  std::map<uint32_t, double> error, mean;
  for (uint32_t bounces : {1u, 2u}) {
    gi::GiSettings s = vctSettings();
    s.vct.bounces = bounces;
    GiRun run(context(), s, "cornell", kSize, kSize);
    run.step(3);
    const render::ImageRgba& ref = cornellReference(run, 2);
    error[bounces] = render::relativeMse(run.hdr(), ref);
    mean[bounces] = lum(render::meanOver(run.hdr())) / lum(render::meanOver(ref));
    dyngi::test::report("vct bounces %u against the path tracer's 2: relMSE %.4f, mean ratio %.3f\n", bounces, error[bounces], mean[bounces]);
  }
  EXPECT_GT(mean[2], mean[1]) << "a second bounce adds light";
  EXPECT_LT(error[2], error[1]);
  EXPECT_NEAR(mean[2], 1.0, 0.1);
}

// The carried light turned on and off while a run goes on (the panel's --bounce-frames): on, it converges
// to what a run with it from the start converges to; off again, the run is a run without it.
TEST_F(RenderTest, VctCarriedLightTurnsOnAndOffWhileRunning) {
  constexpr int kConverged = 3 + 8 * 4;  // eight turns of 4 frames
  gi::GiSettings withCarried = vctSettings();
  withCarried.vct.bounceFrames = 4;
  GiRun run(context(), vctSettings(), "cornell", kSize, kSize), on(context(), withCarried, "cornell", kSize, kSize),
      off(context(), vctSettings(), "cornell", kSize, kSize);
  run.step(3);
  const std::optional<gi::OptionRef> option = gi::findOption(run.gi->technique().options(), "bounce-frames");
  ASSERT_TRUE(option.has_value());
  option->set(4);
  run.step(kConverged);
  on.step(kConverged);
  const double onError = render::relativeMse(run.indirect(), on.indirect());
  option->set(0);
  run.step(8);  // every traced pixel's turn twice over
  off.step(8);
  const double offError = render::relativeMse(run.indirect(), off.indirect());
  dyngi::test::report("turned on: relMSE %.2e against a run with it from the start; off again: %.2e against one without\n", onError, offError);
  EXPECT_LT(onError, 1e-4);
  EXPECT_LT(offError, 1e-6);
  EXPECT_EQ(vctOf(run).stats().carriedUpdated, 0.0);
}

// Under a GI budget the carried light's passes over every voxel (the first frame, a light switched) keep to
// their part as any other frame's; the switched light's carried light is gone at once either way.
TEST_F(RenderTest, VctBudgetSpreadsTheCarriedLightsWholePasses) {
  gi::GiSettings s = vctSettings();
  s.vct.bounceFrames = 4;
  GiRun full(context(), s, "cornell", kSize, kSize), spread(context(), s, "cornell", kSize, kSize);
  spread.gi->technique().spreadOneOffWork(true);
  for (GiRun* run : {&full, &spread}) run->step();
  EXPECT_DOUBLE_EQ(vctOf(full).stats().carriedUpdated, 1.0) << "the first frame updates every voxel";
  EXPECT_DOUBLE_EQ(vctOf(spread).stats().carriedUpdated, 0.25);
  for (GiRun* run : {&full, &spread}) run->step(8);
  EXPECT_DOUBLE_EQ(vctOf(full).stats().carriedUpdated, 0.25);
  const double lit = lum(render::meanOver(spread.indirect()));
  for (GiRun* run : {&full, &spread}) {
    run->world.write<scene::Light>(run->named("spot")).enabled = false;
    run->step();
  }
  EXPECT_DOUBLE_EQ(vctOf(full).stats().carriedUpdated, 1.0) << "unbudgeted, a switched light updates every voxel";
  EXPECT_DOUBLE_EQ(vctOf(spread).stats().carriedUpdated, 0.25);
  EXPECT_LT(lum(render::meanOver(spread.indirect())), 0.01 * lit) << "the old light's carried light is cleared under a budget too";
}

// The bounce light the voxels carry (VctOptions::bounceFrames) adds a bounce each turn: converged, it
// comes closer to the path tracer's full transport (8 bounces) than one or two bounces do, on the whole
// image and on the tail of per-pixel error. A light switched off leaves none of it the frame after; switched
// on again, the light is within 5 percent of where it was after two turns.
TEST_F(RenderTest, VctCarriedBounceLightApproachesEveryBounce) {
  struct Case {
    const char* name;
    uint32_t bounces, bounceFrames;
  };
  const Case cases[] = {{"one bounce", 1, 0}, {"two bounces", 2, 0}, {"carried", 1, 4}};
  std::map<std::string, double> error, mean, p99;
  for (const Case& c : cases) {
    gi::GiSettings s = vctSettings();
    s.vct.bounces = c.bounces;
    s.vct.bounceFrames = c.bounceFrames;
    GiRun run(context(), s, "cornell", kSize, kSize);
    run.step(3 + 8 * c.bounceFrames);  // eight turns of every voxel: eight more bounces
    const render::ImageRgba& ref = cornellReference(run, 8);
    error[c.name] = render::relativeMse(run.hdr(), ref);
    mean[c.name] = lum(render::meanOver(run.hdr())) / lum(render::meanOver(ref));
    p99[c.name] = render::relativeLuminanceErrorQuantile(run.hdr(), ref, 0.99);
    dump(std::string("vct_carried_") + std::to_string(c.bounces) + "_" + std::to_string(c.bounceFrames), run.hdr(), kSize, kSize);
    dyngi::test::report("vct %s against the path tracer's 8 bounces: relMSE %.4f, mean ratio %.3f, p99 relative error %.3f\n", c.name,
                        error[c.name], mean[c.name], p99[c.name]);
    if (c.bounceFrames == 0) continue;
    const render::ImageRgba converged = run.indirect();
    const double lit = lum(render::meanOver(converged));
    run.world.write<scene::Light>(run.named("spot")).enabled = false;
    run.step();
    const double off = lum(render::meanOver(run.indirect()));
    dyngi::test::report("spot switched off: indirect light %.5f -> %.5f one frame later\n", lit, off);
    EXPECT_LT(off, 0.01 * lit) << "the carried light goes with the light";
    // Switched on again: the first bounce is back in that frame (a whole pass), each later one a turn later.
    run.world.write<scene::Light>(run.named("spot")).enabled = true;
    std::vector<render::ImageRgba> frames;
    for (uint32_t f = 0; f < 6 * c.bounceFrames; ++f) {
      run.step();
      frames.push_back(run.indirect());
    }
    const size_t settle = render::settleFrames(frames, converged, 0.05);
    dyngi::test::report("switched on again: indirect within 5%% of the converged light after %zu frames (%u a turn)\n", settle, c.bounceFrames);
    EXPECT_LE(settle, 2 * c.bounceFrames + 1);
  }
  EXPECT_GT(mean["carried"], mean["two bounces"]);
  EXPECT_LT(error["carried"], 0.65 * error["two bounces"]);
  EXPECT_LT(p99["carried"], p99["two bounces"]);
  EXPECT_NEAR(mean["carried"], 1.0, 0.1);
}

namespace {
// A closed 2 m room whose six walls all emit radiance 1 and reflect nothing, the camera at its centre:
// every surface's E / pi is exactly 1 (a furnace test).
void emissiveRoom(ecs::World& w, scene::AssetStore& a) {
  const float h = 1.0f;
  struct Wall { glm::vec3 origin, u, v; };
  const Wall walls[] = {{{-h, -h, h}, {2 * h, 0, 0}, {0, 0, -2 * h}},   // floor, facing +y
                        {{-h, h, -h}, {2 * h, 0, 0}, {0, 0, 2 * h}},    // ceiling, -y
                        {{-h, -h, -h}, {2 * h, 0, 0}, {0, 2 * h, 0}},   // back, +z
                        {{h, -h, h}, {-2 * h, 0, 0}, {0, 2 * h, 0}},    // front, -z
                        {{-h, -h, h}, {0, 0, -2 * h}, {0, 2 * h, 0}},   // left, +x
                        {{h, -h, -h}, {0, 0, 2 * h}, {0, 2 * h, 0}}};   // right, -x
  for (const Wall& wall : walls) {
    const ecs::Entity e = sample::addSceneMesh(w, a, scene::makeQuad(wall.origin, wall.u, wall.v), glm::vec3(0.0f), {}, false, "wall");
    w.write<scene::Material>(e).emissive = glm::vec3(1.0f);
  }
  addActiveCamera(w, scene::Transform{}, 70.0f);
}
}  // namespace

// The diffuse cones' weights (projected solid angle over pi) as vct_cone.glsl's vctDiffuseConeWeight
// computes them: the cones tilted furthest are narrowed to stay above the horizon, so the weights of n
// cones add up to less than 1 (0.80 for 6, 0.88 for 12, 0.93 for 32).
namespace {
double coneWeightSum(uint32_t n) {
  double sum = 0;
  for (uint32_t k = 0; k < n; ++k) {
    const double u = (k + 0.5) / n, z = std::sqrt(std::max(1.0 - u, 0.0));
    const double cosHalf = std::max(1.0 - 1.0 / (2.0 * n * std::max(z, 1e-3)), 0.0);
    double coneTan = std::sqrt(1.0 - cosHalf * cosHalf) / std::max(cosHalf, 1e-3);
    coneTan = std::min(coneTan, 0.9 * z / std::max(std::sqrt(u), 1e-4));
    sum += 2.0 * (1.0 - 1.0 / std::sqrt(1.0 + coneTan * coneTan)) * z;
  }
  return sum;
}
}  // namespace

// What the diffuse cones lose against an analytic truth: in a closed room whose walls all emit radiance
// 1, E / pi is 1 everywhere. The cones' weights add up to coneWeightSum(12) = 0.88 and the band they
// leave uncovered is not made up for: normalising by the weights' sum takes the spot-lit Cornell box
// over the path tracer, where something else gives too much light (docs/QUALITY.md, "Voxel cone
// tracing's energy"). Inside their weight the cones bring back 95 percent (each sample's opacity a
// little under 1 at the walls): 0.84, held here to 92-99 percent of the weights' sum.
TEST_F(RenderTest, VctFurnaceRoomGivesItsRadiance) {
  gi::GiSettings s = vctSettings();
  s.vct.specular = false;
  GiRun run(context(), s, emissiveRoom, 64, 64);
  run.step(3);
  const glm::dvec3 m = render::meanOver(run.indirect());
  dyngi::test::report("furnace: E / pi %.4f %.4f %.4f (exact 1, the cones' weights %.4f)\n", m.r, m.g, m.b, coneWeightSum(s.vct.diffuseCones));
  const double weights = coneWeightSum(s.vct.diffuseCones);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(m[c], 0.92 * weights) << "channel " << c;
    EXPECT_LT(m[c], 0.99 * weights) << "channel " << c;
  }
}


namespace {
// A 4 m floor (albedo 0.5) under a 0.5 m emissive square 1 m up (radiance 5, black), and a dynamic 0.6 m
// square at half height beside it whose umbra covers the floor within 0.35 m of (1, 0, 0).
constexpr float kPanelHalf = 0.25f, kPanelHeight = 1.0f, kPanelRadiance = 5.0f, kFloorAlbedo = 0.5f;
const glm::vec3 kUmbraPoint{1.0f, 0.0f, 0.0f};
void floorUnderPanel(ecs::World& w, scene::AssetStore& a) {
  sample::addSceneMesh(w, a, scene::makeQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}), glm::vec3(kFloorAlbedo), {}, false, "floor");
  const ecs::Entity panel = sample::addSceneMesh(w, a, scene::makeQuad({-kPanelHalf, kPanelHeight, -kPanelHalf}, {2 * kPanelHalf, 0, 0}, {0, 0, 2 * kPanelHalf}),
                                                 glm::vec3(0.0f), {}, false, "panel");
  w.write<scene::Material>(panel).emissive = glm::vec3(kPanelRadiance);
  sample::addSceneMesh(w, a, scene::makeQuad({0.2f, 0.5f, 0.3f}, {0.6f, 0, 0}, {0, 0, -0.6f}), glm::vec3(0.5f), {}, true, "occluder");
  const ecs::Entity bulb = w.create();  // a light besides: switching it leaves the emitter light alone
  scene::Transform bt;
  bt.translation = {-1.0f, 1.5f, 1.0f};
  w.add(bulb, bt);
  w.add(bulb, scene::Light{.type = scene::LightType::Point, .intensity = 0.5f});
  w.add(bulb, scene::Name{"bulb"});
  scene::Transform cam;
  cam.translation = {0.0f, 2.0f, 3.0f};
  cam.rotation = glm::angleAxis(glm::radians(-30.0f), glm::vec3(1, 0, 0));
  addActiveCamera(w, cam, 60.0f);
}

// The panel's unshadowed irradiance at x (facing +y), by brute-force quadrature over it.
double panelIrradiance(const glm::dvec3& x) {
  constexpr int n = 64;
  double e = 0.0;
  const double cell = 2.0 * kPanelHalf / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 y(-kPanelHalf + (i + 0.5) * cell, kPanelHeight, -kPanelHalf + (j + 0.5) * cell);
      const glm::dvec3 d = y - x;
      const double d2 = glm::dot(d, d), c = d.y / std::sqrt(d2);  // both cosines: the panel and the floor are level
      e += kPanelRadiance * c * c / d2 * cell * cell;
    }
  return e;
}

// The carried emitter light of the floor voxels within `radius` m of `at` (the floor's voxel layer), and
// what it should be there unshadowed (albedo E / pi): both means, luminance.
std::pair<double, double> floorEmitterLight(render::VulkanContext& ctx, GiRun& run, glm::vec3 at, float radius) {
  const gi::VoxelVolume vol = run.gi->voxels()->volume();
  const gi::VolumeLevel l0 = readLevels(ctx, vctOf(run).carriedVolume()).front();
  const int y = int(std::floor(vol.toVoxel(glm::vec3(0.0f, 1e-4f, 0.0f)).y));
  const glm::ivec3 c(glm::floor(vol.toVoxel(at)));
  const int r = int(std::ceil(radius / vol.voxelSize));
  double got = 0.0, want = 0.0;
  int n = 0;
  for (int dz = -r; dz <= r; ++dz)
    for (int dx = -r; dx <= r; ++dx) {
      const glm::vec3 centre = vol.toWorld(glm::vec3(c.x + dx, y, c.z + dz) + 0.5f);
      if (glm::distance(glm::vec2(centre.x, centre.z), glm::vec2(at.x, at.z)) > radius) continue;
      const glm::vec4 t = l0.at(c.x + dx, y, c.z + dz);
      if (t.a < 0.5f) continue;  // not a floor voxel (the floor lies in the layer below)
      got += lum(glm::dvec3(glm::vec3(t)));
      want += kFloorAlbedo * panelIrradiance(glm::dvec3(centre)) / std::numbers::pi;
      ++n;
    }
  EXPECT_GT(n, 20) << "floor voxels found around " << at.x << " " << at.z;
  return {got / std::max(n, 1), want / std::max(n, 1)};
}
}  // namespace

// The emitters' light on the voxels (VctOptions::emitterSamples) against brute-force quadrature of the
// panel: under it, with the most samples and with the default few (each voxel's few points differ, so
// a patch's mean still converges); in the umbra of an occluder, none; once the occluder has moved away,
// the unshadowed light again, within the emitterFrames it takes every voxel's turn to come round, and
// kept without a pass while no mesh moves (a light switched included); a brighter panel at once, and
// none once it is switched off.
TEST_F(RenderTest, VctEmitterLightMatchesQuadratureAndFollowsItsShadow) {
  for (uint32_t samples : {uint32_t(DYNGI_VCT_EMITTER_MAX_SAMPLES), gi::VctOptions{}.emitterSamples}) {
    gi::GiSettings s = vctSettings();
    s.vct.emitterSamples = samples;
    GiRun run(context(), s, floorUnderPanel, 64, 64);
    run.step(2);
    ASSERT_TRUE(vctOf(run).carriesEmitterLight());
    const auto [under, underWant] = floorEmitterLight(context(), run, glm::vec3(0.0f), 0.15f);
    const auto [umbra, umbraWant] = floorEmitterLight(context(), run, kUmbraPoint, 0.12f);
    dyngi::test::report("%u samples a voxel: emitter light under the panel %.4f (quadrature %.4f, ratio %.3f); in the umbra %.5f (unshadowed %.4f)\n",
                        samples, under, underWant, under / underWant, umbra, umbraWant);
    EXPECT_NEAR(under / underWant, 1.0, 0.05) << samples;
    EXPECT_LT(umbra, 0.02 * umbraWant) << samples;
    run.world.write<scene::Transform>(run.named("occluder")).translation.z += 2.0f;  // out of the light's way
    run.step(1);
    const uint32_t turn = run.gi->settings().vct.emitterFrames;
    run.step(turn);
    const auto [lit, litWant] = floorEmitterLight(context(), run, kUmbraPoint, 0.12f);
    dyngi::test::report("occluder moved away: %.4f after %u frames (quadrature %.4f, ratio %.3f)\n", lit, turn + 1, litWant, lit / litWant);
    EXPECT_NEAR(lit / litWant, 1.0, 0.08) << samples;
    run.world.write<scene::Light>(run.named("bulb")).enabled = false;
    run.step();  // the turn is over and no mesh moved: the pass is left out, the light kept
    EXPECT_EQ(vctOf(run).stats().carriedUpdated, 0.0) << samples;
    EXPECT_EQ(floorEmitterLight(context(), run, kUmbraPoint, 0.12f).first, lit) << samples;
    // A brighter panel: every voxel's emitter light follows the next frame, not over the turn.
    run.world.write<scene::Material>(run.named("panel")).emissive = glm::vec3(2.0f * kPanelRadiance);
    run.step();
    const double brighter = floorEmitterLight(context(), run, glm::vec3(0.0f), 0.15f).first;
    dyngi::test::report("panel twice as bright: %.4f the next frame (%.3f of twice the quadrature)\n", brighter, brighter / (2.0 * underWant));
    EXPECT_NEAR(brighter / (2.0 * underWant), 1.0, 0.05) << samples;
    run.world.write<scene::Material>(run.named("panel")).emissive = glm::vec3(0.0f);  // switched off: none of it stays
    run.step();
    EXPECT_FALSE(vctOf(run).carriesEmitterLight());
    const std::vector<gi::VolumeLevel> carried = readLevels(context(), vctOf(run).carriedVolume());
    double left = 0.0;
    for (const glm::vec4& t : carried.front().texels) left += t.r + t.g + t.b;
    EXPECT_EQ(left, 0.0) << samples;
  }
}

// The emissive-only Cornell box against the path tracer's 8 bounces: without the emitters' light on the
// voxels the ceiling and the boxes' faces get nothing but what the cones see of the panel; with it the
// image and each of those regions come closer.
TEST_F(RenderTest, VctEmitterLightBringsTheEmissiveRoomCloserToThePathTracer) {
  std::map<uint32_t, double> error, mean;
  std::map<uint32_t, std::map<std::string, double>> regionRatio;
  render::ImageRgba ref;
  for (uint32_t samples : {0u, gi::VctOptions{}.emitterSamples}) {
    gi::GiSettings s = vctSettings();
    s.vct.specular = false;  // the path tracer is Lambert only
    s.vct.emitterSamples = samples;
    GiRun run(context(), s, "cornell-emissive", kSize, kSize);
    run.step(3);
    if (ref.empty()) ref = run.pathTraced(1024, 8);
    const Frame f = run.readFrame();
    error[samples] = render::relativeMse(f.hdr, ref);
    mean[samples] = lum(render::meanOver(f.hdr)) / lum(render::meanOver(ref));
    dump("vct_emitter_light_" + std::to_string(samples), f.hdr, kSize, kSize);
    dyngi::test::report("emissive room, %u emitter samples: relMSE %.4f, mean ratio %.3f; regions", samples, error[samples], mean[samples]);
    for (const auto& [name, mask] : cornellRegions(f, run.assets, kSize).masks) {
      regionRatio[samples][name] = lum(render::meanOver(f.hdr, &mask)) / lum(render::meanOver(ref, &mask));
      dyngi::test::report(" %s %.2f", name.c_str(), regionRatio[samples][name]);
    }
    dyngi::test::report("\n");
  }
  const uint32_t on = gi::VctOptions{}.emitterSamples;
  EXPECT_LT(error[on], 0.6 * error[0]);
  EXPECT_GT(mean[on], mean[0] + 0.05);
  // The regions the panel does not light directly (the ceiling beside it, the boxes' faces turned from
  // it), dark without: at least 0.3 of the path tracer's with it (0.33 to 0.72 measured).
  size_t dark = 0;
  for (const auto& [name, ratio] : regionRatio[0]) {
    if (ratio >= 0.1) continue;
    ++dark;
    EXPECT_GT(regionRatio[on][name], 0.3) << name;
  }
  EXPECT_GE(dark, 4u);
}
