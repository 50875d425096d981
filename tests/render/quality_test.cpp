// What no GI engine measures in its test suite: flicker of a still image and how many frames the GI
// takes to settle after a change, for every technique, on the Cornell box with its spot (64^2, fixed
// time step and seeds, so every figure is the same on every run). Thresholds sit above today's figures
// with a margin, so a regression fails; docs/QUALITY.md keeps the table (scripts/quality_report.sh).
//
// Settle times are measured on the indirect light (the GI's own output, targets.indirect): direct light
// is exact from the first frame in every technique, so the final image would hide the GI's lag behind
// it. Flicker is measured on both.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "support/report.h"
#include "dyngi/engine/render/frame_uniforms.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 64;
constexpr double kSettleTolerance = 0.05;  // within 5 percent (relative L1) of the converged state

// How many frames a technique is run for. The temporal technique's history spans T = 16 frames: it
// converges in about 2 T and is watched for 2 T after a change. Many lights has no history and voxel
// cone tracing's voxel blend halves its error a frame: both are converged long before 16 frames, and a
// slower settle than the ceilings below fails within the 8 frames recorded.
struct Frames {
  int converge;  // frames to converge
  int record;    // frames recorded after a change
  int flicker;   // frames of a still scene whose flicker is measured
};
constexpr Frames kHistoryFrames{36, 32, 60};
constexpr Frames kNoHistoryFrames{16, 8, 16};

struct Config {
  const char* label;
  gi::GiSettings settings;
  size_t maxSettleFrames;  // today's worst case plus a margin
  size_t maxSettleLight;   // the same after a light switched on or moved (goal: 4 frames)
  double maxTrailLag;      // the trail's indirect light after a moving box, relative; today's plus a margin
  double maxPanFlicker;    // the indirect light's reprojected frame-to-frame change under a slow pan
  double maxLeak = 0.05;   // room B's light through a thin wall over its light through a doorway (goal: 0.05)
  Frames frames = kHistoryFrames;
};

std::vector<Config> configs() {
  gi::GiSettings svo;
  svo.technique = "temporal";
  gi::GiSettings bvh = svo;
  bvh.temporal.visibility = gi::VisibilityBackend::Bvh;
  gi::GiSettings rsm;
  rsm.technique = "many-lights";
  // The temporal technique: a light switched on or jumping reshoots every VPL at once (the burst), drops
  // the sets it made stale and gathers four sets a frame until every set is fresh. A box moving into the
  // light invalidates part of the pool: those VPLs are reshot at once, but each set keeps its light until
  // it is gathered again, one a frame (T = 16). Its trail is dark when the box stops and, T frames later,
  // exactly the still run's: invalidated paths are traced again with their own random streams, so the
  // pool is the still run's VPL for VPL. Many lights rebuilds everything every frame: no history.
  // Voxel cone tracing re-injects every frame and traces a quarter of its pixels (trace-frames 4), the
  // rest carried over from up to 3 frames before; a light switched or a jump drops them. A box sliding
  // 3 cm a frame is no jump: its trail's indirect light lags while it moves, the final image's ghosting
  // stays small. Through the 0.05 m wall it leaks under the goal of 5 percent thanks to the far samples'
  // narrowing (VctOptions::farNarrowing; vct_test.cpp compares the mip chains and 256^3). The figures
  // each technique measures here are in docs/QUALITY.md (scripts/quality_report.sh).
  gi::GiSettings vct;
  vct.technique = "vct";
  return {{"temporal (svo)", svo, 18, 5, 0.32, 0.055},
          {"temporal (bvh)", bvh, 18, 5, 0.32, 0.055},
          {"many-lights", rsm, 1, 1, 0.01, 0.045, 0.05, kNoHistoryFrames},
          {"vct", vct, 1, 1, 0.09, 0.035, 0.15, kNoHistoryFrames}};
}

struct SettleFigures {
  size_t frames = 0;     // until within tolerance for good
  double firstError = 0; // relative L1 of the first frame after the change
};

// Runs `change` on a converged run, records the technique's `record` frames of indirect light, and compares them
// with the state they converge to (`converge` frames further on).
template <class Change>
SettleFigures settleAfter(render::VulkanContext& ctx, const Config& c, Change change, bool spotOn = true) {
  GiRun run(ctx, c.settings, "cornell", kSize, kSize);
  if (!spotOn) run.world.write<scene::Light>(run.named("spot")).enabled = false;
  run.step(c.frames.converge);
  change(run);
  std::vector<render::ImageRgba> after;
  for (int i = 0; i < c.frames.record; ++i) {
    run.step();
    after.push_back(run.indirect());
  }
  run.step(c.frames.converge);
  const render::ImageRgba converged = run.indirect();
  return {render::settleFrames(after, converged, kSettleTolerance), render::relativeL1(after.front(), converged)};
}
}  // namespace

// Room B's mean luminance (final image, indirect light) over the pixels that show room B's own surfaces
// (not room A seen through the doorway): the G-buffer position beyond the shared wall.
struct RoomLight {
  double final = 0, indirect = 0;
  size_t pixels = 0;  // how many pixels show room B
};
RoomLight roomB(render::VulkanContext& ctx, const Config& c, const std::string& scene) {
  GiRun run(ctx, c.settings, scene, kSize, kSize);
  run.step(c.frames.converge);
  const Frame f = run.readFrame();
  const render::ImageRgba indirect = run.indirect();
  std::vector<uint8_t> mask(f.position.size(), 0);
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = f.position[i].w != 0.0f && f.position[i].x > 0.0f;  // room B, its side of the shared wall included
  auto lum = [](const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; };
  const size_t pixels = size_t(std::count(mask.begin(), mask.end(), uint8_t(1)));
  return {lum(render::meanOver(f.hdr, &mask)), lum(render::meanOver(indirect, &mask)), pixels};
}

// Light leaking through a wall thinner than two voxels: room B (no light of its own) with the wall
// closed against room B with a doorway in it. The goal is under 5 percent.
TEST_F(RenderTest, QualityLeakThroughAThinWallPerTechnique) {
  dyngi::test::report("quality-leak| technique | room B closed (final, indirect) | room B with a doorway (final, indirect) | leak final | leak indirect\n");
  for (const Config& c : configs()) {
    SCOPED_TRACE(c.label);
    const RoomLight closed = roomB(context(), c, "two-rooms");
    const RoomLight door = roomB(context(), c, "two-rooms-door");
    ASSERT_GT(closed.pixels, size_t(kSize * kSize / 2)) << "the camera sees room B";
    ASSERT_GT(door.pixels, size_t(kSize * kSize / 2));
    ASSERT_GT(door.indirect, 0.0) << "light reaches room B through the doorway";
    const double leakFinal = closed.final / door.final, leakIndirect = closed.indirect / door.indirect;
    dyngi::test::report("quality-leak| %s | %.5f, %.5f | %.5f, %.5f | %.2f%% | %.2f%%\n", c.label, closed.final, closed.indirect, door.final,
                door.indirect, 100 * leakFinal, 100 * leakIndirect);
    EXPECT_LT(leakFinal, c.maxLeak);
    EXPECT_LT(leakIndirect, c.maxLeak);
  }
}

TEST_F(RenderTest, QualityFlickerAndSettleTimePerTechnique) {
  dyngi::test::report("quality| technique | flicker final | flicker indirect | light on: frames, first-frame error | light moved 0.6 m | box moved into the light\n");
  for (const Config& c : configs()) {
    SCOPED_TRACE(c.label);
    // Flicker: a still scene and camera, after convergence.
    GiRun still(context(), c.settings, "cornell", kSize, kSize);
    still.step(c.frames.converge);
    std::vector<render::ImageRgba> finals, indirects;
    for (int i = 0; i < c.frames.flicker; ++i) {
      still.step();
      finals.push_back(still.hdr());
      indirects.push_back(still.indirect());
    }
    const double flickerFinal = render::flicker(finals), flickerIndirect = render::flicker(indirects);
    // Settle after (a) the spot switched on, (b) the spot moved 0.6 m (a third of the room), (c) the tall
    // box moved under the spot.
    const SettleFigures on = settleAfter(
        context(), c, [](GiRun& r) { r.world.write<scene::Light>(r.named("spot")).enabled = true; }, /*spotOn=*/false);
    const SettleFigures moved =
        settleAfter(context(), c, [](GiRun& r) { r.world.write<scene::Transform>(r.named("spot")).translation.x += 0.6f; });
    const SettleFigures box =
        settleAfter(context(), c, [](GiRun& r) { r.world.write<scene::Transform>(r.named("tall_box")).translation = {0.0f, 0.6f, 0.1f}; });
    dyngi::test::report("quality| %s | %.3f%% | %.3f%% | %zu, %.1f%% | %zu, %.1f%% | %zu, %.1f%%\n", c.label, 100 * flickerFinal, 100 * flickerIndirect,
                on.frames, 100 * on.firstError, moved.frames, 100 * moved.firstError, box.frames, 100 * box.firstError);
    // Both techniques converge to a fixed image in a still scene (fixed seeds, no per-frame jitter): any
    // flicker is a regression.
    EXPECT_LT(flickerFinal, 1e-3);
    EXPECT_LT(flickerIndirect, 1e-3);
    EXPECT_LE(on.frames, c.maxSettleLight) << "light switched on";
    EXPECT_LE(moved.frames, c.maxSettleLight) << "light moved";
    EXPECT_LE(box.frames, c.maxSettleFrames) << "box moved into the light";
  }
}

// Flicker under a slow camera pan (0.25 degrees a frame, about a third of a pixel at 64^2, for 60
// frames after convergence): each frame against the previous one reprojected (render::reprojectedChange:
// the same surface point, nearest pixel, disocclusions left out). Nearest-pixel resampling changes
// values by itself where the image has edges, so the direct light's change (final minus albedo x
// indirect; no history in any technique) is printed beside it as the floor that is not the GI's.
TEST_F(RenderTest, QualityFlickerUnderACameraPanPerTechnique) {
  constexpr int kPanFrames = 60;
  constexpr float kDegreesPerFrame = 0.25f, kSamePoint = 0.08f;  // metres: two pixel footprints here (a tap one pixel away)
  dyngi::test::report("quality-pan| technique | final | indirect | direct (resampling floor)\n");
  for (const Config& c : configs()) {
    SCOPED_TRACE(c.label);
    GiRun run(context(), c.settings, "cornell", kSize, kSize);
    ecs::Entity camera{};
    run.world.each<scene::ActiveCamera>([&](ecs::Entity e, const scene::ActiveCamera&) { camera = e; });
    ASSERT_FALSE(camera.isNull());
    const glm::quat start = run.world.get<scene::Transform>(camera).rotation;
    run.step(c.frames.converge);
    struct Shot {
      render::ImageRgba final, indirect, direct, position;
      glm::mat4 viewProj;
    };
    auto shoot = [&] {
      Shot s;
      const Frame f = run.readFrame();
      s.final = f.hdr;
      s.position = f.position;
      s.indirect = run.indirect();
      const render::ImageRgba albedo = run.renderer->readback(render::TargetId::Albedo);
      s.direct = s.final;
      for (size_t i = 0; i < s.direct.size(); ++i)
        s.direct[i] -= glm::vec4(glm::vec3(albedo[i]) * (1.0f - albedo[i].a) * glm::vec3(s.indirect[i]), 0.0f);
      s.viewProj = render::cameraUniforms(f.snapshot.camera, kSize, kSize).viewProj;
      return s;
    };
    Shot previous = shoot();
    double final = 0, indirect = 0, direct = 0;
    for (int i = 1; i <= kPanFrames; ++i) {
      run.world.write<scene::Transform>(camera).rotation =
          glm::angleAxis(glm::radians(kDegreesPerFrame * float(i)), glm::vec3(0, 1, 0)) * start;
      run.step();
      const Shot now = shoot();
      auto change = [&](const render::ImageRgba Shot::*image) {
        return render::reprojectedChange(now.*image, now.position, previous.*image, previous.position, previous.viewProj, kSize, kSize,
                                         kSamePoint) /
               kPanFrames;
      };
      final += change(&Shot::final);
      indirect += change(&Shot::indirect);
      direct += change(&Shot::direct);
      previous = now;
    }
    dyngi::test::report("quality-pan| %s | %.3f%% | %.3f%% | %.3f%%\n", c.label, 100 * final, 100 * indirect, 100 * direct);
    EXPECT_GT(direct, 0.0) << "the camera moved";
    // A black indirect image would change by nothing: the GI must be there to be measured.
    const glm::dvec3 lit = render::meanOver(previous.indirect);
    EXPECT_GT(0.2126 * lit.r + 0.7152 * lit.g + 0.0722 * lit.b, 0.01) << "indirect light on screen";
    EXPECT_LE(indirect, c.maxPanFlicker);
  }
}

// Ghosting: the short box slides 0.9 m across the floor (3 cm a frame for 30 frames). Where it was, the
// floor's light must come back at once. The trail's mean (final image) is compared with the path
// tracer's for the scene as it is now, and with the same technique's error in a run where the box stood
// at its final place all along, so a technique's steady bias is not counted as ghosting.
TEST_F(RenderTest, QualityGhostingBehindAMovingBoxPerTechnique) {
  constexpr int kMoveFrames = 30;
  constexpr float kStep = 0.03f, kStartX = -0.5f, kBoxZ = 0.3f;
  const glm::vec3 finalPlace{kStartX + kStep * kMoveFrames, 0.3f, kBoxZ};
  auto place = [](GiRun& r, glm::vec3 at) {
    scene::Transform& t = r.world.write<scene::Transform>(r.named("short_box"));
    t.translation = at;
    t.rotation = glm::quat(1, 0, 0, 0);
  };
  // The trail: floor left behind by the box (x up to 0.3 m short of its final left face), inside its
  // z extent.
  auto trailMask = [&](const Frame& f) {
    std::vector<uint8_t> mask(f.position.size(), 0);
    for (size_t i = 0; i < mask.size(); ++i) {
      const glm::vec4 p = f.position[i];
      mask[i] = p.w != 0.0f && std::abs(p.y) < 0.01f && p.x > kStartX - 0.25f && p.x < finalPlace.x - 0.3f - 0.3f &&
                std::abs(p.z - kBoxZ) < 0.25f;
    }
    return mask;
  };
  auto lum = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  dyngi::test::report("quality-ghost| technique | trail vs path tracer, moving | same, box there all along | ghosting (final) | trail's indirect, moving vs all along | the same, another seed vs all along\n");
  double reference = -1;
  for (Config c : configs()) {
    SCOPED_TRACE(c.label);
    // 4096 VPLs: with 512 the trail's indirect light differs by 15-22 percent between two seeds, which
    // would hide any lag.
    c.settings.temporal.vpl.vpls = c.settings.manyLights.vpl.vpls = 4096;
    GiRun moving(context(), c.settings, "cornell", kSize, kSize);
    place(moving, {kStartX, 0.3f, kBoxZ});
    moving.step(c.frames.converge);
    for (int i = 1; i <= kMoveFrames; ++i) {
      place(moving, {kStartX + kStep * float(i), 0.3f, kBoxZ});
      moving.step();
    }
    const Frame m = moving.readFrame();
    const render::ImageRgba movingIndirect = moving.indirect();
    GiRun still(context(), c.settings, "cornell", kSize, kSize);
    place(still, finalPlace);
    still.step(c.frames.converge);
    const Frame st = still.readFrame();
    const render::ImageRgba stillIndirect = still.indirect();
    // The same still run with other VPLs (seed): how far two converged runs differ in the trail anyway
    // (a technique without random numbers, voxel cone tracing, is its own reseeded run).
    gi::GiSettings reseeded = c.settings;
    reseeded.temporal.vpl.seed = reseeded.manyLights.vpl.seed = 7;
    render::ImageRgba still2Indirect = stillIndirect;
    if (c.settings.technique != "vct") {
      GiRun still2(context(), reseeded, "cornell", kSize, kSize);
      place(still2, finalPlace);
      still2.step(c.frames.converge);
      still2Indirect = still2.indirect();
    }
    const std::vector<uint8_t> mask = trailMask(st);
    const size_t pixels = size_t(std::count(mask.begin(), mask.end(), uint8_t(1)));
    ASSERT_GT(pixels, 20u) << "the trail is in view";
    if (reference < 0) reference = lum(render::meanOver(still.pathTraced(1024, 1), &mask));
    ASSERT_GT(reference, 0.0);
    const double errMoving = lum(render::meanOver(m.hdr, &mask)) / reference - 1.0;
    const double errStill = lum(render::meanOver(st.hdr, &mask)) / reference - 1.0;
    // The GI's own lag: the trail's indirect light against the run where the box stood there all along.
    const double lag = lum(render::meanOver(movingIndirect, &mask)) / lum(render::meanOver(stillIndirect, &mask)) - 1.0;
    const double seedToSeed = lum(render::meanOver(still2Indirect, &mask)) / lum(render::meanOver(stillIndirect, &mask)) - 1.0;
    dyngi::test::report("quality-ghost| %s | %+.1f%% | %+.1f%% | %.1f%% | %+.1f%% | %+.1f%%\n", c.label, 100 * errMoving, 100 * errStill,
                100 * std::abs(errMoving - errStill), 100 * lag, 100 * seedToSeed);
    EXPECT_LT(std::abs(errMoving - errStill), 0.03) << "ghosting in the final image";
    EXPECT_LT(std::abs(lag), c.maxTrailLag) << "the trail's indirect light lags";
    // Once every temporal set has been gathered again, nothing of the motion is left: the same light as
    // the run where the box stood there all along.
    moving.step(c.settings.temporal.temporalSets);
    const double settled = lum(render::meanOver(moving.indirect(), &mask)) / lum(render::meanOver(stillIndirect, &mask)) - 1.0;
    dyngi::test::report("quality-ghost| %s | %u frames later: %+.2f%%\n", c.label, c.settings.temporal.temporalSets, 100 * settled);
    EXPECT_LT(std::abs(settled), 0.005) << "the motion left a lasting difference";
  }
}
