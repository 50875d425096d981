// The reference path tracer against analytic truths.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "dyngi/engine/render/image_metrics.h"
#include "dyngi/engine/scene/light_units.h"
#include "dyngi/engine/scene/transform_system.h"
#include "dyngi/gi/path_tracer.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::scene;

namespace {
constexpr float kPi = 3.14159265358979f;

struct Scene {
  ecs::World world;
  AssetStore assets;
  gi::EmbreeScene bvh;
  render::RenderSnapshot snapshot() {
    ecs::Scheduler s;
    s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
    s.runFrame(world, {});
    bvh.sync(world, assets, 0);
    return render::extractSnapshot(world, assets, 0);
  }
  Entity add(MeshData m, const Material& mat, const Transform& t = {}) {
    Entity e = world.create();
    world.add(e, t);
    world.add(e, MeshInstance{assets.addMesh(std::move(m)), true});
    world.add(e, mat);
    return e;
  }
  void camera(const glm::vec3& pos, const glm::vec3& dir, float yfov) {
    Entity c = world.create();
    Transform t;
    t.translation = pos;
    t.rotation = glm::quatLookAtRH(glm::normalize(dir), std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0));
    world.add(c, t);
    world.add(c, Camera{.yfov = yfov});
    world.add(c, ActiveCamera{});
  }
};
}  // namespace

TEST(PathTracer, FurnaceConvergesToEmissionOverOneMinusAlbedo) {
  for (float albedo : {0.5f, 0.8f}) {
    Scene s;
    const float le = 1.0f;
    s.add(makeSphere(1.0f, 48, 24), Material{.baseColor = glm::vec4(albedo, albedo, albedo, 1), .emissive = glm::vec3(le)});
    s.camera({0, 0, 0}, {0, 0, -1}, 1.2f);
    gi::PathTracerSettings pts;
    pts.spp = 32;
    pts.bounces = 64;  // 0.8^64 ~ 6e-7: truncation is far below the noise
    auto img = gi::pathTrace(s.snapshot(), s.bvh, s.assets, 32, 32, pts);
    double mean = render::meanOver(img).x;
    EXPECT_NEAR(mean, le / (1.0f - albedo), 0.015 * le / (1.0f - albedo)) << "albedo " << albedo;
  }
}

TEST(PathTracer, FloorUnderPointLightIsExactWithoutBounces) {
  Scene s;
  const float albedo = 0.5f;
  s.add(makeQuad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}), Material{.baseColor = glm::vec4(albedo, albedo, albedo, 1)});
  Light light;
  light.type = LightType::Point;
  light.intensity = 5.0f;
  Entity le = s.world.create();
  Transform lt;
  lt.translation = {0.3f, 1.5f, -0.2f};
  s.world.add(le, lt);
  s.world.add(le, light);
  s.camera({0, 3, 0}, {0, -1, 0}, 1.0f);
  auto snap = s.snapshot();
  gi::PathTracerSettings pts;
  pts.spp = 2;
  pts.bounces = 0;
  pts.pixelJitter = false;  // compare exactly at the pixel centres
  const uint32_t n = 48;
  auto img = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);
  glm::mat4 inv = glm::inverse(snap.camera.projection(1.0f) * snap.camera.view);
  int checked = 0;
  for (uint32_t y = 1; y + 1 < n; ++y)
    for (uint32_t x = 1; x + 1 < n; ++x) {
      glm::vec4 f = inv * glm::vec4((float(x) + 0.5f) / float(n) * 2 - 1, (float(y) + 0.5f) / float(n) * 2 - 1, 1, 1);
      glm::vec3 d = glm::normalize(glm::vec3(f) / f.w - snap.camera.position);
      gi::RayHit h = s.bvh.intersect(snap.camera.position, d, 0, 100);
      if (!h.hit) continue;
      glm::vec3 p = snap.camera.position + d * h.t;
      if (std::abs(p.x) > 1.9f || std::abs(p.z) > 1.9f) continue;  // pixels straddling the quad's edge
      float e = directIrradiance(light, lt.translation, {0, 0, -1}, p, {0, 1, 0}).r;
      EXPECT_NEAR(img[size_t(y) * n + x].r, albedo / kPi * e, 1e-3f * albedo / kPi * e) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 1000);
}

TEST(PathTracer, ErrorFallsLikeOneOverSqrtSpp) {
  Scene s;
  sample::buildBuiltinScene("cornell", s.world, s.assets);
  auto snap = s.snapshot();
  const uint32_t n = 40;
  gi::PathTracerSettings pts;
  pts.bounces = 1;
  pts.spp = 1024;
  pts.seed = 99;
  auto ref = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);
  pts.seed = 7;
  pts.spp = 8;
  double e8 = render::rmse(gi::pathTrace(snap, s.bvh, s.assets, n, n, pts), ref);
  pts.spp = 32;
  double e32 = render::rmse(gi::pathTrace(snap, s.bvh, s.assets, n, n, pts), ref);
  pts.spp = 128;
  double e128 = render::rmse(gi::pathTrace(snap, s.bvh, s.assets, n, n, pts), ref);
  // Four times the samples halves the error (the reference's own noise makes the last ratio a bit smaller).
  EXPECT_NEAR(e8 / e32, 2.0, 0.35);
  EXPECT_NEAR(e32 / e128, 2.0, 0.45);
}

TEST(PathTracer, IndirectLightAddsEnergyAndColourBleeds) {
  Scene s;
  sample::buildBuiltinScene("cornell", s.world, s.assets);
  auto snap = s.snapshot();
  gi::PathTracerSettings pts;
  pts.spp = 64;
  pts.bounces = 0;
  auto direct = gi::pathTrace(snap, s.bvh, s.assets, 32, 32, pts);
  pts.bounces = 2;
  auto gi2 = gi::pathTrace(snap, s.bvh, s.assets, 32, 32, pts);
  glm::dvec3 md = render::meanOver(direct), mg = render::meanOver(gi2);
  EXPECT_GT(mg.x, md.x * 1.2) << "bounces add light";
  // Ceiling: no direct light at all, lit only by bounces.
  EXPECT_EQ(direct[size_t(1) * 32 + 16].r, 0.0f);
  EXPECT_GT(gi2[size_t(1) * 32 + 16].r, 0.0f);
}
