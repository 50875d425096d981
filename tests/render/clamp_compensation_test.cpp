// The distance clamp without its lost energy: the gather's G = cos cos / max(B, d^2) drops the
// light of VPLs closer than sqrt(B); the compensation (indirect/shaders/compensate.comp, added by the
// merge filter's second pass) gives it back from short screen-space rays. Checked against the path
// tracer: the room's corner strips (where the clamp takes most), and the tail of the per-pixel error
// against the path tracer's own seed-to-seed noise (the 99th-percentile target).
#include <gtest/gtest.h>

#include <cstdio>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/scripted_motion.h"
#include "render/cornell_regions.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 128;

// spread: VplOptions::clampSpread (the screen-space compensation's own figures are measured without it).
gi::GiSettings vplSettings(const std::string& technique, uint32_t bounces, float clamp, uint32_t rays,
                           float spread = gi::VplOptions{}.clampSpread) {
  gi::GiSettings s;
  s.technique = technique;
  gi::VplOptions& v = technique == "temporal" ? s.temporal.vpl : s.manyLights.vpl;
  v.vpls = 1024;
  v.bounces = bounces;
  v.bounceTail = false;  // against the path tracer with as many bounces
  v.distanceClamp = clamp;
  v.clampCompensation = rays;
  v.clampSpread = spread;
  return s;
}
gi::GiSettings temporalSettings(uint32_t bounces, float clamp, uint32_t rays, float spread) {
  return vplSettings("temporal", bounces, clamp, rays, spread);
}

// The corner strips of the built-in Cornell box: surface points within `reach` of a second plane of the
// room (the floor, the ceiling, the back and side walls), the boxes' bases included (within reach of the
// floor on a vertical face).
std::vector<uint8_t> cornerStrips(const Frame& f, float reach, size_t& count) {
  std::vector<uint8_t> mask(f.position.size(), 0);
  count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const glm::vec4 p = f.position[i];
    if (p.w == 0.0f) continue;
    const glm::vec3 n = glm::vec3(f.normal[i]);
    int near = 0;
    // Planes the point is close to but not on (its own plane is where its normal points away from).
    if (p.y < reach && std::abs(n.y) < 0.5f) ++near;                  // the floor, seen from a vertical face
    if (p.y > 2.0f - reach && std::abs(n.y) < 0.5f) ++near;           // the ceiling
    if (p.z < -1.0f + reach && std::abs(n.z) < 0.5f) ++near;          // the back wall
    if (std::abs(p.x) > 1.0f - reach && std::abs(n.x) < 0.5f) ++near;  // a side wall
    if (near > 0) mask[i] = 1, ++count;
  }
  return mask;
}

double ratioOver(const render::ImageRgba& a, const render::ImageRgba& ref, const std::vector<uint8_t>& mask) {
  return luminance(render::meanOver(a, &mask)) / luminance(render::meanOver(ref, &mask));
}
}  // namespace

TEST_F(RenderTest, ClampCompensationGivesTheCornersTheirLightBack) {
  // One bounce: the VPLs stand for the direct light where they lie, which the compensation's rays read
  // from the same surfaces (emission + shadowed direct light). Both VPL techniques share the pass.
  render::ImageRgba reference;
  for (const char* technique : {"temporal", "many-lights"}) {
    SCOPED_TRACE(technique);
    double corner[2] = {0, 0}, image[2] = {0, 0};
    for (uint32_t rays : {0u, 8u}) {
      GiRun run(context(), vplSettings(technique, 1, 0.08f, rays, 0.0f), "cornell", kSize, kSize);
      run.step(20);
      Frame f = run.readFrame();
      if (reference.empty()) reference = run.pathTraced(256, 1);
      size_t n = 0;
      std::vector<uint8_t> strips = cornerStrips(f, 0.15f, n);
      ASSERT_GT(n, 500u);
      corner[rays > 0] = ratioOver(f.hdr, reference, strips);
      image[rays > 0] = luminance(render::meanOver(f.hdr)) / luminance(render::meanOver(reference));
      dyngi::test::report("%-11s compensation rays %u: corner strips (%zu px) %.3f, image %.3f of the path tracer's\n", technique, rays, n,
                  corner[rays > 0], image[rays > 0]);
    }
    // Measured: temporal 0.857 -> 0.927 of the path tracer in the strips, image 0.970 -> 0.981; many
    // lights 0.849 -> 0.919, 0.970 -> 0.980. Not all of it: rays that leave the screen or pass behind an edge find nothing
    // (the compensation never invents light).
    EXPECT_LT(corner[0], 0.9) << "without the compensation the clamp darkens the corners";
    EXPECT_GT(corner[1], corner[0] + 0.05) << "the compensation gives the corners most of their light back";
    EXPECT_LT(corner[1], 1.03) << "and no more";
    EXPECT_LT(std::abs(image[1] - 1.0), std::abs(image[0] - 1.0));
  }
}

TEST_F(RenderTest, VplImageErrorTailStaysWithinTwiceThePathTracersOwnNoise) {
  // The measure: the 99th percentile of the per-pixel relative luminance error of the default
  // technique (temporal VPL paths, SVO visibility; 1024 VPLs, 3 bounces, converged) against the path
  // tracer with the same bounces, at most 2x the path tracer's own seed-to-seed 99th percentile at the
  // spp used: with the defaults (B = 0.01, no compensation), and with B = 0.08 and the compensation,
  // which must improve both the tail and relMSE. Measured (paths from the R3 sequence): p99 0.617
  // (defaults) and 0.578, the path tracer's own 0.669 (512 spp); relMSE 0.00515 and 0.00481. At the
  // issue's size, 256^2 against 2048 spp, the defaults measure 0.48-0.52 against 0.311 (docs/QUALITY.md).
  gi::EmbreeScene bvh;
  render::ImageRgba refs[2];
  auto run = [&](float clamp, uint32_t rays, float spread) {
    GiRun r(context(), temporalSettings(3, clamp, rays, spread), "cornell", kSize, kSize);
    r.step(40);
    if (refs[0].empty()) {
      bvh.sync(r.world, r.assets, 0);
      for (uint64_t seed : {1u, 2u}) {
        gi::PathTracerSettings pts;
        pts.spp = 512;
        pts.bounces = 3;
        pts.pixelJitter = false;
        pts.seed = seed;
        refs[seed - 1] = gi::pathTrace(render::extractSnapshot(r.world, r.assets, r.frame), bvh, r.assets, kSize, kSize, pts);
      }
    }
    return r.hdr();
  };
  const render::ImageRgba defaults = run(gi::VplOptions{}.distanceClamp, 0, gi::VplOptions{}.clampSpread), compensated = run(0.08f, 8, 0.0f);
  const double noise = render::relativeLuminanceErrorQuantile(refs[1], refs[0], 0.99);
  const double tailDefaults = render::relativeLuminanceErrorQuantile(defaults, refs[0], 0.99);
  const double tailCompensated = render::relativeLuminanceErrorQuantile(compensated, refs[0], 0.99);
  const double relMseDefaults = render::relativeMse(defaults, refs[0]), relMseCompensated = render::relativeMse(compensated, refs[0]);
  dyngi::test::report("p99 relative luminance error: defaults %.3f, B 0.08 with compensation %.3f; path tracer seed to seed %.3f; relMSE %.5f, %.5f\n",
              tailDefaults, tailCompensated, noise, relMseDefaults, relMseCompensated);
  EXPECT_LE(tailDefaults, 2.0 * noise);
  EXPECT_LE(tailCompensated, 2.0 * noise);
  EXPECT_LT(tailCompensated, tailDefaults);
  EXPECT_LE(relMseCompensated, relMseDefaults);
}

// The clamp spread (shared/clamp_spread.h, on by default: a bump of reach sqrt(B) stretched 8 times along
// the corner): the light the clamp drops comes back spread near where it lands. One bounce, the default
// B = 0.01, 1024 VPLs, 128^2, against the path tracer at 512 spp. Measured: temporal (SVO visibility)
// corner strips 0.954 -> 0.991, image 0.988 -> 0.992; many lights 0.935 -> 0.971, 0.981 -> 0.986
// (0.998 and 0.978 with a stretch of 4 before the spread looked at the screen,
// ClampSpreadLeavesABoxFaceBesideLitFloorDark; docs/QUALITY.md).
TEST_F(RenderTest, ClampSpreadGivesTheCornersTheirLightBack) {
  render::ImageRgba reference;
  for (const char* technique : {"temporal", "many-lights"}) {
    SCOPED_TRACE(technique);
    double corner[2] = {0, 0}, image[2] = {0, 0};
    for (bool spread : {false, true}) {
      const float reach = spread ? gi::VplOptions{}.clampSpread : 0.0f;
      ASSERT_TRUE(!spread || reach > 0.0f) << "the spread is on by default";
      gi::GiSettings s = vplSettings(technique, 1, gi::VplOptions{}.distanceClamp, 0, reach);
      GiRun run(context(), s, "cornell", kSize, kSize);
      run.step(20);
      Frame f = run.readFrame();
      if (reference.empty()) reference = run.pathTraced(512, 1);
      size_t n = 0;
      std::vector<uint8_t> strips = cornerStrips(f, 0.15f, n);
      corner[spread] = ratioOver(f.hdr, reference, strips);
      image[spread] = luminance(render::meanOver(f.hdr)) / luminance(render::meanOver(reference));
      dyngi::test::report("%-11s clamp spread %d: corner strips (%zu px) %.3f, image %.3f of the path tracer's\n", technique, int(spread), n,
                  corner[spread], image[spread]);
    }
    EXPECT_GT(corner[1], corner[0] + 0.015) << "the spread gives the corners light back";
    EXPECT_LT(corner[1], 1.03) << "and no more than they lost";
    EXPECT_LT(std::abs(image[1] - 1.0), std::abs(image[0] - 1.0));
  }
}

// The spread takes the receiver's surface to run on past it; a box's face does not. In the main job's
// last frame the short box's front face is in its own shadow, and so is the floor in front of it, while
// the floor beside the box is lit: VPLs there sit on the face's plane extended, where the clamp dropped
// their light on nothing. Spread along the face's base, that light showed as a bright smear on a face
// the path tracer has dark there. The gather now looks at the screen where the spread lays the light
// (spreadPlaneShown in gather.glsl) and gives nothing back where the face is not. The main job's
// technique and settings at 192^2 after its 60 frames, against the path tracer at 512 spp: the base strip
// (within 0.12 m of the floor) of the face's interior pixels, and the room's corner strips, which must
// keep their light. Measured: base strip 1.714 -> 0.879, corner strips 0.989 -> 0.982. (Many lights,
// whose 512 RSM VPLs are drawn anew each frame, reads 1.57 -> 1.51 there: its noise, not the smear.)
TEST_F(RenderTest, ClampSpreadLeavesABoxFaceBesideLitFloorDark) {
  constexpr uint32_t size = 192;
  gi::GiSettings s = vplSettings("temporal", 1, gi::VplOptions{}.distanceClamp, 0);
  s.temporal.vpl.vpls = gi::VplOptions{}.vpls;  // the main job's
  GiRun run(context(), s, "cornell-dynamic", size, size);
  run.scheduler.add(ecs::Phase::Update, std::make_unique<scene::ScriptedMotionSystem>());  // the boxes and the spot move
  run.step(60);
  Frame f = run.readFrame();
  const render::ImageRgba reference = run.pathTraced(512, 1);
  dumpTestImage("spread_face", f.hdr, size, size);
  dumpTestImage("spread_face_path", reference, size, size);
  Regions regions = cornellRegions(f, run.assets, size);
  ASSERT_TRUE(regions.masks.count("short_box +z"));
  std::vector<uint8_t> base = regions.masks.at("short_box +z");
  size_t n = 0;
  for (size_t i = 0; i < base.size(); ++i) {
    base[i] = base[i] && f.position[i].y < 0.12f;
    n += base[i];
  }
  ASSERT_GT(n, 100u);
  size_t nCorners = 0;
  const std::vector<uint8_t> corners = cornerStrips(f, 0.15f, nCorners);
  const double baseRatio = ratioOver(f.hdr, reference, base), cornerRatio = ratioOver(f.hdr, reference, corners);
  dyngi::test::report("short box's front face, base strip (%zu px): %.3f of the path tracer; corner strips (%zu px) %.3f\n", n, baseRatio,
              nCorners, cornerRatio);
  EXPECT_NEAR(baseRatio, 1.0, 0.25) << "no smear along the base";
  EXPECT_NEAR(cornerRatio, 1.0, 0.05) << "the room's corners keep their light";
}
