// Degenerate inputs the renderer must survive with a sane, checked result.
#include <gtest/gtest.h>

#include "dyngi/engine/render/image_io.h"
#include "render/render_fixture.h"
#include "support/temp_dir.h"

using namespace dyngi;
using namespace dyngi::test;

TEST_F(RenderTest, ZeroLightsShowsEmissionOnly) {
  ecs::World w;
  scene::AssetStore assets;
  scene::Entity e = w.create();
  w.add(e, scene::Transform{});
  w.add(e, scene::MeshInstance{assets.addMesh(scene::makeQuad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0})), true});
  w.add(e, scene::Material{.baseColor = glm::vec4(0.8f), .emissive = glm::vec3(0.25f, 0.5f, 1.0f)});
  Frame f = render(w, assets, 64, 64);
  int covered = 0;
  for (size_t i = 0; i < f.hdr.size(); ++i) {
    if (f.position[i].w > 0.5f) {
      ++covered;
      EXPECT_NEAR(f.hdr[i].r, 0.25f, 1e-3f);
      EXPECT_NEAR(f.hdr[i].g, 0.5f, 1e-3f);
      EXPECT_NEAR(f.hdr[i].b, 1.0f, 1e-3f);
    } else {
      EXPECT_EQ(f.hdr[i].r, 0.0f);
    }
  }
  EXPECT_GT(covered, 64 * 64 / 4) << "the auto-framed camera sees the quad";
}

TEST_F(RenderTest, EmptySceneRendersBackground) {
  ecs::World w;
  scene::AssetStore assets;
  render::RendererSettings s;
  s.background = {0.1f, 0.2f, 0.3f};
  Frame f = render(w, assets, 32, 16, s);
  for (auto& px : f.hdr) {
    EXPECT_FLOAT_EQ(px.r, 0.1f);
    EXPECT_FLOAT_EQ(px.b, 0.3f);
  }
}

TEST_F(RenderTest, ResizeRefusesZeroAndKeepsWorking) {
  render::Renderer r(context());
  EXPECT_FALSE(r.resize(0, 0));
  EXPECT_FALSE(r.resize(0, 64));
  ASSERT_TRUE(r.resize(1, 1));
  ecs::World w;
  scene::AssetStore assets;
  r.render(render::extractSnapshot(w, assets, 0));
  EXPECT_FALSE(r.resize(0, 0));
  EXPECT_EQ(r.width(), 1u);
  ASSERT_TRUE(r.resize(33, 17));  // odd sizes: dispatch rounding
  r.render(render::extractSnapshot(w, assets, 1));
  EXPECT_EQ(r.readback(render::TargetId::Hdr).size(), 33u * 17u);
}

TEST_F(RenderTest, ObjectFarOutsideTheSceneStillRendersAndShadowsStayFinite) {
  ecs::World w;
  scene::AssetStore assets;
  auto add = [&](scene::MeshData m, glm::vec3 at) {
    scene::Entity e = w.create();
    scene::Transform t;
    t.translation = at;
    w.add(e, t);
    w.add(e, scene::MeshInstance{assets.addMesh(std::move(m)), true});
    w.add(e, scene::Material{});
  };
  add(scene::makeBox(glm::vec3(0.5f)), {0, 0, 0});
  add(scene::makeBox(glm::vec3(0.5f)), {0, 0, -5000});  // stretches the bounds enormously
  scene::Entity l = w.create();
  scene::Transform lt;
  lt.translation = {0, 3, 2};
  w.add(l, lt);
  w.add(l, scene::Light{.type = scene::LightType::Point, .intensity = 4.0f});
  Frame f = render(w, assets, 64, 64);
  for (auto& px : f.hdr) {
    ASSERT_TRUE(std::isfinite(px.r) && std::isfinite(px.g) && std::isfinite(px.b));
  }
}

TEST_F(RenderTest, HdrSurvivesExrRoundTrip) {
  ecs::World w;
  scene::AssetStore assets;
  scene::Entity e = w.create();
  w.add(e, scene::Transform{});
  w.add(e, scene::MeshInstance{assets.addMesh(scene::makeSphere(1.0f, 16, 8)), true});
  w.add(e, scene::Material{.emissive = glm::vec3(3.5f, 0.125f, 42.0f)});
  Frame f = render(w, assets, 24, 24);
  TempDir dir;
  std::string path = dir.file("x.exr");
  ASSERT_EQ(render::writeExr(path, f.width, f.height, f.hdr), "");
  uint32_t rw = 0, rh = 0;
  std::vector<glm::vec4> back;
  ASSERT_EQ(render::readExr(path, rw, rh, back), "");
  ASSERT_EQ(rw, 24u);
  ASSERT_EQ(rh, 24u);
  for (size_t i = 0; i < back.size(); ++i) EXPECT_EQ(back[i].b, f.hdr[i].b);
  ASSERT_EQ(render::writePng(dir.file("x.png"), f.width, f.height, f.ldr), "");
}
