#include <gtest/gtest.h>

#include "support/shared_scenes.h"

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/engine/scene/animation.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "dyngi/engine/scene/transform_system.h"

using namespace dyngi;
using namespace dyngi::scene;

TEST(AnimationSampling, StepLinearAndCubicMatchHandValues) {
  AnimationChannel c;
  c.path = AnimationPath::Translation;
  c.times = {0.0f, 1.0f, 3.0f};
  c.values = {{0, 0, 0, 0}, {2, 4, 6, 0}, {4, 0, 0, 0}};
  c.interpolation = Interpolation::Step;
  EXPECT_EQ(sampleChannel(c, 0.99f).x, 0.0f);
  EXPECT_EQ(sampleChannel(c, 1.5f).x, 2.0f);
  c.interpolation = Interpolation::Linear;
  EXPECT_NEAR(sampleChannel(c, 0.25f).y, 1.0f, 1e-6f);
  EXPECT_NEAR(sampleChannel(c, 2.0f).x, 3.0f, 1e-6f);
  EXPECT_EQ(sampleChannel(c, -5.0f).x, 0.0f) << "clamped before the first key";
  EXPECT_EQ(sampleChannel(c, 50.0f).x, 4.0f) << "clamped after the last key";

  // Cubic spline: p(u) with p0=0, p1=1, tangents m0 = m1 = 0 gives smoothstep 3u^2 - 2u^3;
  // with unit tangents over a 2 s interval the curve is the straight line (Hermite reproduces lines).
  AnimationChannel s;
  s.path = AnimationPath::Translation;
  s.interpolation = Interpolation::CubicSpline;
  s.times = {0.0f, 2.0f};
  s.values = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0.5f, 0, 0}, {0, 0.5f, 0, 0}, {1, 1, 0, 0}, {0, 0, 0, 0}};
  float u = 0.3f;
  EXPECT_NEAR(sampleChannel(s, 2.0f * u).x, 3 * u * u - 2 * u * u * u, 1e-5f);
  EXPECT_NEAR(sampleChannel(s, 2.0f * u).y, u, 1e-5f);
}

TEST(AnimationSampling, LinearRotationIsNormalisedSlerp) {
  AnimationChannel c;
  c.path = AnimationPath::Rotation;
  c.interpolation = Interpolation::Linear;
  c.times = {0.0f, 1.0f};
  glm::quat a = glm::angleAxis(0.0f, glm::vec3(0, 1, 0)), b = glm::angleAxis(2.0f, glm::vec3(0, 1, 0));
  c.values = {{a.x, a.y, a.z, a.w}, {b.x, b.y, b.z, b.w}};
  glm::vec4 v = sampleChannel(c, 0.25f);
  glm::quat q(v.w, v.x, v.y, v.z);
  EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::angle(q), 0.5f, 1e-4f) << "a quarter of the way along a 2 rad turn";
}

TEST(Skinning, TwoBoneBarBendsExactly) {
  // A bar along +X from 0 to 2; vertices with x < 1 follow joint 0 (identity), the others joint 1,
  // which rotates 90 degrees about Z around the point (1,0,0).
  MeshData bind;
  for (float x : {0.0f, 0.5f, 1.5f, 2.0f}) {
    bind.positions.push_back({x, 0, 0});
    bind.normals.push_back({0, 1, 0});
    bind.joints.push_back(glm::uvec4(x < 1.0f ? 0u : 1u, 0, 0, 0));
    bind.weights.push_back({1, 0, 0, 0});
  }
  glm::mat4 j1 = glm::translate(glm::mat4(1), {1, 0, 0}) * glm::rotate(glm::mat4(1), glm::radians(90.0f), {0, 0, 1}) *
                 glm::translate(glm::mat4(1), {-1, 0, 0});
  MeshData out;
  skinMesh(bind, {glm::mat4(1.0f), j1}, out);
  EXPECT_NEAR(glm::distance(out.positions[1], glm::vec3(0.5f, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(out.positions[2], glm::vec3(1, 0.5f, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(out.positions[3], glm::vec3(1, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(out.normals[3], glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
  // Half-and-half weights blend the two matrices.
  bind.joints[3] = glm::uvec4(0, 1, 0, 0);
  bind.weights[3] = glm::vec4(0.5f, 0.5f, 0, 0);
  skinMesh(bind, {glm::mat4(1.0f), j1}, out);
  EXPECT_NEAR(glm::distance(out.positions[3], 0.5f * (glm::vec3(2, 0, 0) + glm::vec3(1, 1, 0))), 0.0f, 1e-6f);
}

TEST(Skinning, FoxWalksAndStaysConsistent) {
  DYNGI_SHARED_SCENE_OR_SKIP(path, "Fox.glb");
  ecs::World w;
  AssetStore assets;
  ImportReport report;
  ImportOptions opts;
  opts.clip = "Walk";
  ASSERT_EQ(importGltf(path, w, assets, &report, opts), "");
  EXPECT_EQ(report.skinnedMeshes, 1u);
  EXPECT_EQ(report.clips, (std::vector<std::string>{"Survey", "Walk", "Run"}));
  EXPECT_FALSE(report.missingClip);
  ecs::Scheduler s;
  s.add(ecs::Phase::Update, std::make_unique<AnimationSystem>());
  s.add(ecs::Phase::PostUpdate, std::make_unique<TransformSystem>());
  auto& skinning = static_cast<SkinningSystem&>(s.add(ecs::Phase::PostUpdate, std::make_unique<SkinningSystem>(assets)));
  MeshId deformed = 0, bindPose = 0;
  w.each<SkinnedMesh>([&](Entity, const SkinnedMesh& sm) { deformed = sm.deformed, bindPose = sm.bindPose; });
  std::vector<glm::vec3> previous;
  uint32_t lastVersion = assets.mesh(deformed).version;
  for (int f = 0; f < 20; ++f) {
    s.runFrame(w, ecs::FrameTime{1.0 / 30.0, f / 30.0, uint64_t(f)});
    EXPECT_EQ(skinning.meshesSkinnedLastRun(), 1u) << "walking moves joints every frame";
    const MeshData& m = assets.mesh(deformed);
    EXPECT_GT(m.version, lastVersion) << "the version bump is what tells consumers to re-upload/refit";
    lastVersion = m.version;
    if (!previous.empty()) {
      float moved = 0;
      for (size_t i = 0; i < m.positions.size(); ++i) moved = std::max(moved, glm::distance(m.positions[i], previous[i]));
      EXPECT_GT(moved, 0.1f) << "frame " << f;
    }
    previous = m.positions;
  }
  // Deformed normals agree with the deformed faces.
  const MeshData& m = assets.mesh(deformed);
  double agree = 0;
  int n = 0;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    glm::vec3 fn = glm::cross(m.positions[m.indices[t + 1]] - m.positions[m.indices[t]], m.positions[m.indices[t + 2]] - m.positions[m.indices[t]]);
    if (glm::length(fn) < 1e-9f) continue;
    agree += glm::dot(glm::normalize(fn), m.normals[m.indices[t]]);
    ++n;
  }
  EXPECT_GT(agree / n, 0.9);
  EXPECT_EQ(assets.mesh(bindPose).positions.size(), m.positions.size());
}
