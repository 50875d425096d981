// The reference path tracer against analytic truths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

namespace {
// The form factor from a point to a parallel rectangle whose corner lies straight above it, a by b at
// height c (the classic closed form); signed in a and b so that four of them make any rectangle.
double cornerFormFactor(double a, double b, double c) {
  const double A = std::abs(a) / c, B = std::abs(b) / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  const double f = (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
  return (a < 0) == (b < 0) ? f : -f;
}
double rectangleFormFactor(glm::dvec2 p, glm::dvec2 lo, glm::dvec2 hi, double c) {
  return cornerFormFactor(hi.x - p.x, hi.y - p.y, c) - cornerFormFactor(lo.x - p.x, hi.y - p.y, c) -
         cornerFormFactor(hi.x - p.x, lo.y - p.y, c) + cornerFormFactor(lo.x - p.x, lo.y - p.y, c);
}
}  // namespace

// A grey floor under a black emissive square: radiance albedo x Le x F(point -> square) in closed form.
// Sampling the square has a thirtieth of the error of finding it by bounces alone.
TEST(PathTracer, FloorUnderEmissiveSquareMatchesTheFormFactor) {
  Scene s;
  const float albedo = 0.5f, le = 3.0f, height = 1.0f;
  s.add(makeQuad({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}), Material{.baseColor = glm::vec4(albedo, albedo, albedo, 1)});
  s.add(makeQuad({-0.5f, height, -0.5f}, {1, 0, 0}, {0, 0, 1}), Material{.baseColor = glm::vec4(0, 0, 0, 1), .emissive = glm::vec3(le)});
  s.camera({0, 0.9f, 0}, {0, -1, 0}, 1.6f);  // under the square, seeing the floor under it and around it
  auto snap = s.snapshot();
  gi::PathTracerSettings pts;
  pts.spp = 256;
  pts.bounces = 1;  // the emitter's light on the floor is one bounce
  pts.pixelJitter = false;
  const uint32_t n = 32;
  const auto nee = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);
  pts.emitterSampling = false;
  const auto bouncesOnly = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);

  render::ImageRgba truth(nee.size(), glm::vec4(0, 0, 0, 1));
  const glm::mat4 inv = glm::inverse(snap.camera.projection(1.0f) * snap.camera.view);
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const glm::vec4 f = inv * glm::vec4((float(x) + 0.5f) / float(n) * 2 - 1, (float(y) + 0.5f) / float(n) * 2 - 1, 1, 1);
      const glm::vec3 d = glm::normalize(glm::vec3(f) / f.w - snap.camera.position);
      const glm::vec3 p = snap.camera.position + d * (snap.camera.position.y / -d.y);
      const double ff = rectangleFormFactor({p.x, p.z}, {-0.5, -0.5}, {0.5, 0.5}, height);
      truth[size_t(y) * n + x] = glm::vec4(glm::vec3(float(albedo * le * ff)), 1.0f);
    }
  const double meanTruth = render::meanOver(truth).x;
  ASSERT_GT(meanTruth, 0.1);
  EXPECT_NEAR(render::meanOver(nee).x, meanTruth, 0.005 * meanTruth);
  EXPECT_NEAR(render::meanOver(bouncesOnly).x, meanTruth, 0.05 * meanTruth) << "both strategies are unbiased";
  const double neeError = render::relativeMse(nee, truth), bounceError = render::relativeMse(bouncesOnly, truth);
  EXPECT_LT(neeError, 0.001);  // 0.0006 measured: noise alone, it falls as 1 / spp
  EXPECT_LT(neeError, bounceError / 10) << "sampling the emitter removes most of the noise";
  EXPECT_LT(render::relativeLuminanceErrorQuantile(nee, truth, 0.99), 0.12);
}

namespace {
double seedToSeedRelativeMse(Scene& s, const render::RenderSnapshot& snap, uint32_t n, gi::PathTracerSettings pts) {
  pts.seed = 11;
  const auto a = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);
  pts.seed = 12;
  const auto b = gi::pathTrace(snap, s.bvh, s.assets, n, n, pts);
  return render::relativeMse(a, b);
}
}  // namespace

// The emissive-only Cornell box converges like the spot-lit one, and sampling the emitter changes the
// noise, not the mean.
TEST(PathTracer, EmissiveRoomConvergesLikeASpotLitOne) {
  const uint32_t n = 32;
  gi::PathTracerSettings pts;
  pts.spp = 256;
  pts.bounces = 8;
  Scene spot, lamp;
  sample::buildBuiltinScene("cornell", spot.world, spot.assets);
  sample::buildBuiltinScene("cornell-emissive", lamp.world, lamp.assets);
  const auto spotSnap = spot.snapshot(), lampSnap = lamp.snapshot();
  const double spotNoise = seedToSeedRelativeMse(spot, spotSnap, n, pts);
  const double lampNoise = seedToSeedRelativeMse(lamp, lampSnap, n, pts);
  pts.emitterSampling = false;
  const double lampNoiseBouncesOnly = seedToSeedRelativeMse(lamp, lampSnap, n, pts);
  std::printf("seed-to-seed relMSE at 256 spp: spot-lit %.4f, emissive %.4f, emissive by bounces only %.4f\n", spotNoise, lampNoise,
              lampNoiseBouncesOnly);
  EXPECT_LT(lampNoise, 2.0 * spotNoise);
  EXPECT_GT(lampNoiseBouncesOnly, 5.0 * lampNoise);

  pts.spp = 1024;
  const glm::dvec3 bouncesOnly = render::meanOver(gi::pathTrace(lampSnap, lamp.bvh, lamp.assets, n, n, pts));
  pts.emitterSampling = true;
  const glm::dvec3 sampled = render::meanOver(gi::pathTrace(lampSnap, lamp.bvh, lamp.assets, n, n, pts));
  std::printf("mean at 1024 spp: sampled %.4f %.4f %.4f, bounces only %.4f %.4f %.4f\n", sampled.x, sampled.y, sampled.z,
              bouncesOnly.x, bouncesOnly.y, bouncesOnly.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sampled[c], bouncesOnly[c], 0.02 * bouncesOnly[c]) << "channel " << c;
}
