// The two renderers agree where they must: the path tracer at --bounces 0 and the rasterizer with GI
// off compute the same direct light; the CPU tone map equals the GPU one.
#include <gtest/gtest.h>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/gi/path_tracer.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

TEST_F(RenderTest, PathTracerDirectMatchesRasterizerPerRegion) {
  ecs::World w;
  scene::AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  const uint32_t n = 128;
  Frame raster = render(w, assets, n, n);
  gi::EmbreeScene bvh;
  bvh.sync(w, assets, 0);
  gi::PathTracerSettings pts;
  // With no bounces the estimate is deterministic; sample pixel centres as the rasterizer does, so region
  // masks taken from the G-buffer select the same surface points.
  pts.spp = 1;
  pts.bounces = 0;
  pts.pixelJitter = false;
  render::ImageRgba pt = gi::pathTrace(raster.snapshot, bvh, assets, n, n, pts);

  struct Region {
    const char* name;
    std::function<bool(const glm::vec4& p, const glm::vec4& nrm)> in;
  };
  const Region regions[] = {
      {"floor", [](auto& p, auto& q) { return std::abs(p.y) < 1e-3f && q.y > 0.99f; }},
      {"left wall", [](auto& p, auto& q) { return p.x < -0.999f && q.x > 0.99f; }},
      {"right wall", [](auto& p, auto& q) { return p.x > 0.999f && q.x < -0.99f; }},
      {"back wall", [](auto& p, auto& q) { return p.z < -0.999f && q.z > 0.99f; }},
  };
  for (const Region& r : regions) {
    // Interior pixels only: on a one-pixel boundary the rasterizer and the ray may pick the two
    // different surfaces that meet there (wall vs floor at a corner).
    auto inside = [&](uint32_t x, uint32_t y) {
      size_t i = size_t(y) * n + x;
      return raster.position[i].w > 0.5f && r.in(raster.position[i], raster.normal[i]);
    };
    std::vector<uint8_t> mask(raster.hdr.size(), 0);
    int count = 0;
    for (uint32_t y = 1; y + 1 < n; ++y)
      for (uint32_t x = 1; x + 1 < n; ++x)
        if (inside(x, y) && inside(x - 1, y) && inside(x + 1, y) && inside(x, y - 1) && inside(x, y + 1))
          mask[size_t(y) * n + x] = 1, ++count;
    ASSERT_GT(count, 200) << r.name;
    glm::dvec3 a = render::meanOver(raster.hdr, &mask), b = render::meanOver(pt, &mask);
    double la = a.x + a.y + a.z, lb = b.x + b.y + b.z;
    ASSERT_GT(lb, 1e-4) << r.name << " is lit";
    dyngi::test::report("%-10s raster/path-tracer mean radiance = %.4f (%d px)\n", r.name, la / lb, count);
    EXPECT_NEAR(la / lb, 1.0, 0.02) << r.name << ": raster " << la << " vs path tracer " << lb;
  }
}

TEST_F(RenderTest, CpuToneMapEqualsGpuToneMap) {
  ecs::World w;
  scene::AssetStore assets;
  sample::buildBuiltinScene("cornell", w, assets);
  render::RendererSettings s;
  s.exposure = 1.7f;
  Frame f = render(w, assets, 96, 96, s);
  std::vector<uint8_t> cpu = render::tonemapToSrgb8(f.hdr, s.exposure, s.toneMapper);
  int worst = 0;
  for (size_t i = 0; i < cpu.size(); ++i) worst = std::max(worst, std::abs(int(cpu[i]) - int(f.ldr[i])));
  EXPECT_LE(worst, 1) << "at most one 8-bit step apart";
}
