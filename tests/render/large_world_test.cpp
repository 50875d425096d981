// The GI in a world far larger than a room: the built-in 400 m "street" and its near copy ("street-near",
// only what lies within 40 m of the camera along the street). The voxel volume covers the camera's
// surroundings (VoxelSettings::reach), so near the camera the voxel techniques see what they see in the
// near copy, and SVO visibility comes to Embree's.
#include <gtest/gtest.h>

#include "support/report.h"
#include "dyngi/engine/render/image_metrics.h"
#include "render/gi_run.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

namespace {
constexpr uint32_t kWidth = 128, kHeight = 96;
constexpr int kFrames = 36;  // the temporal technique's 16 sets twice over

double lum(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The north facade on the left of the view, never sunlit: its light is the GI's alone
// (scripts/large_world.sh uses the same rectangle).
std::vector<uint8_t> facadeMask(const Frame& f) {
  std::vector<uint8_t> mask(f.position.size(), 0);
  for (uint32_t y = kHeight * 15 / 100; y < kHeight * 40 / 100; ++y)
    for (uint32_t x = kWidth * 3 / 100; x < kWidth * 30 / 100; ++x) mask[y * kWidth + x] = f.position[y * kWidth + x].w != 0.0f;
  return mask;
}

struct StreetRun {
  double facade = 0;  // the facade's mean indirect luminance
  float voxelSize = 0;
  bool windowed = false;
  Frame frame;
  render::ImageRgba indirect;
};
StreetRun runStreet(render::VulkanContext& ctx, const gi::GiSettings& s, const char* scene = "street") {
  GiRun run(ctx, s, scene, kWidth, kHeight);
  run.step(kFrames);
  StreetRun r;
  r.frame = run.readFrame();
  r.indirect = run.indirect();
  const std::vector<uint8_t> mask = facadeMask(r.frame);
  r.facade = lum(render::meanOver(r.indirect, &mask));
  if (const gi::VoxelScene* v = run.gi->voxels()) {
    r.voxelSize = v->volume().voxelSize;
    r.windowed = v->stats().windowed;
  }
  return r;
}
}  // namespace

// SVO visibility over voxels of the scene's size (3.4 m over 400 m) blocked most segments that end near
// a surface, the facade's light among them; over the camera's surroundings it is Embree's exact
// visibility within its own noise. The run over the whole scene (reach 0) shows the test can fail.
TEST_F(RenderTest, SvoVisibilityInAWideWorldComesToEmbreesNearTheCamera) {
  gi::GiSettings svo;
  svo.technique = "temporal";
  gi::GiSettings bvh = svo;
  bvh.temporal.visibility = gi::VisibilityBackend::Bvh;
  gi::GiSettings whole = svo;
  whole.voxels.reach = 0.0f;
  const StreetRun a = runStreet(context(), svo), b = runStreet(context(), bvh), c = runStreet(context(), whole);
  report("street facade, indirect luminance: SVO over the camera's surroundings %.4f (voxel %.2f m), Embree %.4f, SVO over the "
         "scene %.4f (voxel %.2f m): %.2f and %.2f of Embree's\n",
         a.facade, a.voxelSize, b.facade, c.facade, c.voxelSize, a.facade / b.facade, c.facade / b.facade);
  EXPECT_TRUE(a.windowed);
  EXPECT_FALSE(c.windowed);
  EXPECT_LT(a.voxelSize, 1.0f) << "a voxel the size of a street's detail";
  EXPECT_GT(c.voxelSize, 3.0f);
  ASSERT_GT(b.facade, 0.0);
  EXPECT_NEAR(a.facade / b.facade, 1.0, 0.12);
  EXPECT_LT(c.facade / b.facade, 0.7) << "voxels of the scene's size block the facade's light";
}

// Near the camera, each technique sees the same in the street as in its near copy: the pixels that show
// the same surface in both (the near copy's blocks and ground, short of its cut) have the same indirect
// light. The temporal technique's VPLs differ between the two (the sun's over the focus in the street,
// over the whole near copy) and the street's blocks past the cut bounce some light back: 3.5 percent
// brighter in the street at the commit that added this test.
TEST_F(RenderTest, NearTheCameraTheStreetLooksAsItsNearCopy) {
  struct Case {
    const char* technique;
    double maxRelMse, maxMeanError;
  };
  for (const Case& k : {Case{"vct", 0.02, 0.03}, Case{"temporal", 0.02, 0.05}}) {
    gi::GiSettings s;
    s.technique = k.technique;
    const StreetRun full = runStreet(context(), s, "street"), near = runStreet(context(), s, "street-near");
    std::vector<uint8_t> same(full.frame.position.size(), 0);
    size_t count = 0;
    for (size_t i = 0; i < same.size(); ++i) {
      const glm::vec4 p = full.frame.position[i], q = near.frame.position[i];
      same[i] = p.w != 0.0f && q.w != 0.0f && glm::length(glm::vec3(p) - glm::vec3(q)) < 0.01f &&
                p.x < sample::StreetLayout::kCamera.x + sample::StreetLayout::kNearReach - 10.0f;
      count += same[i];
    }
    const double ratio = lum(render::meanOver(full.indirect, &same)) / lum(render::meanOver(near.indirect, &same));
    const double rel = render::relativeMse(full.indirect, near.indirect, &same);
    report("%s near the camera, street against street-near (%zu pixels; voxels %.2f and %.2f m): mean ratio %.3f, relMSE %.4f; "
           "facade %.4f and %.4f\n",
           k.technique, count, full.voxelSize, near.voxelSize, ratio, rel, full.facade, near.facade);
    EXPECT_GT(count, size_t(kWidth * kHeight / 3)) << k.technique;
    EXPECT_TRUE(full.windowed) << k.technique;
    EXPECT_NEAR(ratio, 1.0, k.maxMeanError) << k.technique;
    EXPECT_LE(rel, k.maxRelMse) << k.technique;
  }
}
