// The raster passes draw instanced batches (render::drawBatched): each instance must get its own
// transform and material from the frame's records, whichever batch and slot it lands in. The truth is
// the world itself: every pixel's surface must lie inside the instance its position names, with that
// instance's base colour, metallic and roughness in the G-buffer.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "render/render_fixture.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr int kSide = 8;  // instances per row and column, 1 m apart, centred on the origin

struct Instance {
  glm::vec2 centre;
  float half;  // half the quad's side after its scale
  scene::Material material;
};

// kSide^2 quads facing +z: two meshes of the same shape alternating in an irregular pattern (so the
// batches of one mesh are not neighbours in draw order), each instance with its own scale and material.
std::vector<Instance> quadGrid(ecs::World& w, scene::AssetStore& a) {
  const scene::MeshId meshes[2] = {a.addMesh(scene::makeQuad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0})),
                                   a.addMesh(scene::makeQuad({-0.5f, -0.5f, 0}, {1, 0, 0}, {0, 1, 0}))};
  std::vector<Instance> out;
  for (int k = 0; k < kSide * kSide; ++k) {
    Instance in;
    in.centre = glm::vec2(k % kSide, k / kSide) - glm::vec2(0.5f * (kSide - 1));
    const float scale = 0.5f + 0.4f * float((k * 7) % 4) / 3.0f;
    in.half = 0.5f * scale;
    in.material = scene::Material{.baseColor = glm::vec4((float(k % kSide) + 0.5f) / float(kSide), (float(k / kSide) + 0.5f) / float(kSide), 0.2f + 0.6f * float(k % 2), 1.0f),
                                  .metallic = float(k % 5) / 5.0f,
                                  .roughness = 0.2f + 0.6f * float(k % 7) / 6.0f};
    const ecs::Entity e = w.create();
    scene::Transform t;
    t.translation = glm::vec3(in.centre, 0.0f);
    t.scale = glm::vec3(scale);
    w.add(e, t);
    w.add(e, scene::MeshInstance{meshes[(k % 3 == 0) ? 1 : 0], true});
    w.add(e, in.material);
    out.push_back(in);
  }
  const ecs::Entity sun = w.create();
  scene::Transform st;
  st.translation = {0, 0, 5};
  w.add(sun, st);  // local -Z: towards the grid
  w.add(sun, scene::Light{.type = scene::LightType::Directional, .intensity = 2.0f});
  const ecs::Entity cam = w.create();
  scene::Transform ct;
  ct.translation = {0.0f, 0.0f, 9.0f};
  w.add(cam, ct);  // looks down -Z at the grid
  w.add(cam, scene::Camera{.yfov = 1.0f});
  w.add(cam, scene::ActiveCamera{});
  return out;
}
}  // namespace

TEST_F(RenderTest, InstancedDrawsGiveEachInstanceItsOwnTransformAndMaterial) {
  ecs::World world;
  scene::AssetStore assets;
  const std::vector<Instance> grid = quadGrid(world, assets);
  constexpr uint32_t kSize = 160;
  Frame f = render(world, assets, kSize, kSize);
  const float pixelWorld = 2.0f * 9.0f * std::tan(0.5f) / float(kSize);  // a pixel's side on the grid's plane

  std::vector<int> pixels(grid.size(), 0);
  std::vector<float> reach(grid.size(), 0.0f);  // how far from its centre an instance's pixels lie
  int wrongMaterial = 0, outside = 0;
  for (size_t p = 0; p < f.position.size(); ++p) {
    const glm::vec4& pos = f.position[p];
    if (pos.w < 0.5f) continue;
    const glm::ivec2 cell = glm::ivec2(glm::round(glm::vec2(pos) + glm::vec2(0.5f * (kSide - 1))));
    ASSERT_TRUE(cell.x >= 0 && cell.y >= 0 && cell.x < kSide && cell.y < kSide) << "a surface off the grid at " << pos.x << ", " << pos.y;
    const size_t k = size_t(cell.y * kSide + cell.x);
    const Instance& in = grid[k];
    const glm::vec2 d = glm::abs(glm::vec2(pos) - in.centre);
    reach[k] = std::max(reach[k], std::max(d.x, d.y));
    if (std::max(d.x, d.y) > in.half + 1e-3f) ++outside;
    ++pixels[k];
    const glm::vec4 albedo = f.albedo[p];
    const glm::vec4 expected(glm::vec3(in.material.baseColor), in.material.metallic);
    if (glm::any(glm::greaterThan(glm::abs(albedo - expected), glm::vec4(1.5f / 255.0f))) ||
        std::abs(f.normal[p].w - in.material.roughness) > 2e-3f)
      ++wrongMaterial;
  }
  EXPECT_EQ(outside, 0) << "pixels beyond their instance's scaled quad: a transform from another slot";
  EXPECT_EQ(wrongMaterial, 0) << "pixels with another instance's base colour, metallic or roughness";
  for (size_t k = 0; k < grid.size(); ++k) {
    // Every instance drawn, to its own size: its pixels reach to within two pixels of its edge.
    EXPECT_GT(pixels[k], 0) << "instance " << k << " not drawn";
    EXPECT_GT(reach[k], grid[k].half - 2.0f * pixelWorld) << "instance " << k << " smaller than its scale";
  }
}
