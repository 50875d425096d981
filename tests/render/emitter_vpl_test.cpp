// Emissive surfaces as VPL sources (gi_module/vpl/emitters.h) in both VPL techniques, against the path
// tracer at the same bounce count: the Cornell box with its spot replaced by an emissive panel under the
// ceiling (the only light), and the shared CornellBox.glb when ../shared is there.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "render/cornell_regions.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "support/shared_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kSize = 128;
constexpr glm::vec3 kLampRadiance{6.0f, 5.4f, 4.2f};

// The built-in Cornell box lit only by a 0.5 m emissive panel hanging 10 cm under the ceiling,
// facing down (emitters are two-sided: its back lights the ceiling).
void cornellWithALamp(ecs::World& w, scene::AssetStore& a) {
  sample::buildBuiltinScene("cornell", w, a);
  std::vector<ecs::Entity> lights;
  w.each<scene::Light>([&](ecs::Entity e, const scene::Light&) { lights.push_back(e); });
  for (ecs::Entity e : lights) w.destroy(e);
  const ecs::Entity lamp =
      sample::addSceneMesh(w, a, scene::makeQuad({-0.25f, 1.9f, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}), glm::vec3(0.75f), {}, false, "lamp");
  w.write<scene::Material>(lamp).emissive = kLampRadiance;
}

struct Case {
  const char* name;
  gi::GiSettings settings;
};
std::vector<Case> cases(uint32_t bounces) {
  std::vector<Case> out;
  for (const char* name : {"svo", "bvh", "many-lights"}) {
    gi::GiSettings s;
    s.technique = std::string(name) == "many-lights" ? "many-lights" : "temporal";
    s.temporal.visibility = std::string(name) == "bvh" ? gi::VisibilityBackend::Bvh : gi::VisibilityBackend::Svo;
    // Against the path tracer with as many bounces: no tail unless a test asks for it.
    for (gi::VplOptions* v : {&s.temporal.vpl, &s.manyLights.vpl}) v->vpls = 1024 * bounces, v->bounces = bounces, v->bounceTail = false;
    s.temporal.temporalSets = 1;
    s.temporal.reshootBudget = 1024 * bounces;
    out.push_back({name, s});
  }
  return out;
}
}  // namespace

TEST_F(RenderTest, EmissivePanelLightsTheRoomThroughBothVplTechniques) {
  for (uint32_t bounces : {1u, 2u}) {
    render::ImageRgba reference;
    for (const Case& c : cases(bounces)) {
      GiRun run(context(), c.settings, cornellWithALamp, kSize, kSize);
      run.step(3);
      const Frame f = run.readFrame();
      if (reference.empty()) reference = run.pathTraced(512, bounces);
      dumpTestImage(std::string("emitter_") + c.name + "_" + std::to_string(bounces), f.hdr, kSize, kSize);
      if (c.name == std::string("svo")) dumpTestImage("emitter_path_" + std::to_string(bounces), reference, kSize, kSize);
      const Regions regions = cornellRegions(f, run.assets, kSize);
      ASSERT_GE(regions.masks.size(), 8u);
      double worst = 0, brightest = 0;
      for (const auto& [name, mask] : regions.masks) brightest = std::max(brightest, luminance(render::meanOver(reference, &mask)));
      for (const auto& [name, mask] : regions.masks) {
        size_t n = 0;
        for (uint8_t m : mask) n += m;
        const double a = luminance(render::meanOver(f.hdr, &mask)), b = luminance(render::meanOver(reference, &mask));
        if (n < 60 || b < 1e-3) continue;  // too small to average, or unlit (the boxes' faces the panel is behind)
        dyngi::test::report("%-11s bounces %u  %-16s %.4f / %.4f = %.3f\n", c.name, bounces, name.c_str(), a, b, a / b);
        worst = std::max(worst, std::abs(a / b - 1.0));
        // 15 percent (measured: 3.6% at worst with one bounce for the temporal paths, 6.5% for many
        // lights; with two, 6.2% and 12%). The faces only the second bounce reaches (the short box's
        // front, at a tenth of the ceiling) were 36% dark with random temporal paths, whose few VPLs on
        // the floor before it clumped; with R3 paths 6% bright; many lights' are 11% and 14.5% dark:
        // held to 20%.
        const double tolerance = bounces == 1 || b >= 0.1 * brightest ? 0.15 : 0.20;
        EXPECT_NEAR(a / b, 1.0, tolerance) << c.name << ", " << bounces << " bounce(s): " << name;
      }
      const double rel = render::relativeMse(f.hdr, reference);
      dyngi::test::report("%-11s bounces %u  worst region %.1f%% off, relMSE %.4f\n", c.name, bounces, 100 * worst, rel);
    }
  }
}

// "cornell-emissive": the lamp hangs 2 cm under the ceiling, closer than SVO visibility lifts a segment's
// end off its surface (1.5 voxels, 2.6 cm). The VPLs its back leaves on the ceiling would start their
// segments under the lamp and light the room through it (the temporal technique's floor was 51 percent
// bright with 3 bounces); they are left out of the gather, as Embree visibility leaves them out by their
// own rays. Many lights bounce on the GPU from a lifted start, so the lamp's back sends its rays out
// through the ceiling instead: no VPLs there to leak (10-13 percent dark, the light escaping the gap).
// Then the same with the bounce tail against 8 bounces: the tail holds in an emissive room too.
TEST_F(RenderTest, LampUnderTheCeilingDoesNotLightTheRoomThroughItself) {
  constexpr uint32_t kBounces = 3;
  auto build = [](ecs::World& w, scene::AssetStore& a) { sample::buildBuiltinScene("cornell-emissive", w, a); };
  for (const bool tail : {false, true}) {
    render::ImageRgba reference;
    for (Case c : cases(kBounces)) {
      c.settings.temporal.vpl.bounceTail = c.settings.manyLights.vpl.bounceTail = tail;
      GiRun run(context(), c.settings, build, kSize, kSize);
      run.step(3);
      const Frame f = run.readFrame();
      if (reference.empty()) reference = run.pathTraced(256, tail ? 8 : kBounces);  // regions of 1000+ pixels: 256 spp is ample
      dumpTestImage(std::string("emitter_lamp_") + c.name + (tail ? "_tail" : ""), f.hdr, kSize, kSize);
      const Regions regions = cornellRegions(f, run.assets, kSize);
      ASSERT_TRUE(regions.masks.count("floor"));
      size_t checked = 0;
      for (const auto& [name, mask] : regions.masks) {
        size_t n = 0;
        for (uint8_t m : mask) n += m;
        const double a = luminance(render::meanOver(f.hdr, &mask)), b = luminance(render::meanOver(reference, &mask));
        dyngi::test::report("lamp %-11s tail %-3s %-16s %5zu px %.4f / %.4f = %.3f\n", c.name, tail ? "on" : "off", name.c_str(), n, a,
                            b, a / b);
        // Left out: the boxes' faces (the tail of the error, not this leak) and the ceiling, which the
        // lamp lights at grazing angles only, where the VPLs' clamp and its spread decide (0.82 SVO,
        // 1.83 Embree, 0.71 many lights).
        if (n < 60 || name.find("box") != std::string::npos || name == "ceiling") continue;
        EXPECT_NEAR(a / b, 1.0, 0.15) << c.name << (tail ? ", tail" : "") << ": " << name;
        ++checked;
      }
      EXPECT_GE(checked, 4u) << c.name;
    }
  }
}

// The shared scene an artist would try first: CornellBox.glb, lit only by its emissive ceiling panel
// (imported with KHR_materials_emissive_strength). The path tracer is Lambert only, and so are the VPLs.
TEST_F(RenderTest, SharedEmissiveCornellBoxLightsTheRoomThroughBothVplTechniques) {
  DYNGI_SHARED_SCENE_OR_SKIP(path, "CornellBox.glb");
  constexpr uint32_t kSharedSize = 96;
  render::ImageRgba reference;
  for (const Case& c : cases(1)) {
    GiRun run(
        context(), c.settings, [&](ecs::World& w, scene::AssetStore& a) { ASSERT_EQ(scene::importGltf(path, w, a), ""); }, kSharedSize,
        kSharedSize);
    run.step(3);
    const Frame f = run.readFrame();
    if (reference.empty()) reference = run.pathTraced(2048, 1);
    dumpTestImage(std::string("emitter_shared_") + c.name, f.hdr, kSharedSize, kSharedSize);
    if (c.name == std::string("svo")) dumpTestImage("emitter_shared_path", reference, kSharedSize, kSharedSize);
    // Surfaces by their G-buffer normal (the scene's own walls, not the built-in box's regions); the
    // emitter's own pixels (brighter than 1) left out.
    const std::pair<const char*, glm::vec3> surfaces[] = {
        {"floor", {0, 1, 0}}, {"left wall", {1, 0, 0}}, {"right wall", {-1, 0, 0}}, {"back wall", {0, 0, 1}}};
    // The ceiling is left out: the panel lies a few millimetres under it and lights it at grazing angles
    // only (the path tracer's 0.0019, under 1% of the floor), where a VPL's cosine is 0.
    size_t checked = 0;
    for (const auto& [name, normal] : surfaces) {
      size_t n = 0;
      const std::vector<uint8_t> mask = surfaceFacing(f, reference, normal, n);
      const double a = luminance(render::meanOver(f.hdr, &mask)), b = luminance(render::meanOver(reference, &mask));
      if (n < 100 || b < 1e-3) continue;
      dyngi::test::report("shared CornellBox.glb %-11s %-10s %.4f / %.4f = %.3f (%zu px)\n", c.name, name, a, b, a / b, n);
      EXPECT_NEAR(a / b, 1.0, 0.15) << c.name << ": " << name;
      ++checked;
    }
    EXPECT_GE(checked, 4u) << c.name;
  }
}

// The panel switched off (its emission set to 0, a material edit): the indirect light it made is gone
// within a few frames in both techniques at their defaults (the temporal one: 16 sets, stale sets dropped).
TEST_F(RenderTest, EmissivePanelSwitchedOffTakesItsIndirectLightAway) {
  for (const char* technique : {"temporal", "many-lights"}) {
    gi::GiSettings s;
    s.technique = technique;
    GiRun run(context(), s, cornellWithALamp, 64, 64);
    run.step(24);
    const double lit = luminance(render::meanOver(run.indirect()));
    ASSERT_GT(lit, 1e-3) << technique;
    run.world.write<scene::Material>(run.named("lamp")).emissive = glm::vec3(0.0f);
    int frames = 0;
    double now = lit;
    while (frames < 10 && now > 0.01 * lit) run.step(), ++frames, now = luminance(render::meanOver(run.indirect()));
    dyngi::test::report("%-11s indirect %.4f -> under 1%% after %d frame(s) (%.5f)\n", technique, lit, frames, now);
    EXPECT_LE(frames, 2) << technique;
  }
}
