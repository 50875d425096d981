// assets/cornell_box.gltf, the scene the embedding example (examples/minimal_host) renders: the file in
// the tree is its generator's output, and it renders as the built-in Cornell box it was written from.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/report.h"
#include "dyngi/engine/scene/gltf_import.h"
#include "render/gi_run.h"
#include "support/example_scene.h"

using namespace dyngi;
using namespace dyngi::test;

TEST(ExampleScene, CommittedGltfIsItsGeneratorsOutput) {
  std::ifstream f(DYNGI_ASSETS_DIR "/cornell_box.gltf", std::ios::binary);
  ASSERT_TRUE(f) << "assets/cornell_box.gltf is missing";
  std::stringstream text;
  text << f.rdbuf();
  // Compared whole, reported briefly (the file is 7 kB of one line).
  EXPECT_TRUE(text.str() == cornellBoxGltf()) << "assets/cornell_box.gltf differs from its generator: regenerate it with build/bin/dyngi_make_example_scene";
}

// The same technique over both worlds gives the same image: geometry, materials, light units, the spot's
// orientation and the camera all survive the trip through glTF.
TEST_F(RenderTest, ExampleGltfRendersAsTheBuiltinCornellBox) {
  gi::GiSettings s;
  s.technique = "many-lights";  // no history: one frame is its image
  GiRun builtin(context(), s, "cornell", 96, 96);
  GiRun imported(
      context(), s,
      [](ecs::World& w, scene::AssetStore& a) {
        const std::string err = scene::importGltf(DYNGI_ASSETS_DIR "/cornell_box.gltf", w, a);
        ASSERT_TRUE(err.empty()) << err;
      },
      96, 96);
  builtin.step(2);
  imported.step(2);
  const render::ImageRgba a = builtin.hdr(), b = imported.hdr();
  const glm::dvec3 mean = render::meanOver(a);
  ASSERT_GT(mean.r + mean.g + mean.b, 0.01) << "the built-in scene is lit";
  EXPECT_LT(render::relativeMse(b, a), 1e-4);
  const render::ImageRgba ia = builtin.indirect(), ib = imported.indirect();
  EXPECT_LT(render::relativeMse(ib, ia), 1e-4) << "the same indirect light";
}

// The showcase scene (an uplight on the ceiling, builtin_scenes.h) is there to show bounce light first:
// most of what is lit on screen gets more light from the GI than from the lamp.
TEST_F(RenderTest, ShowcaseSceneIsLitMostlyByBounceLight) {
  gi::GiSettings s;
  s.technique = "many-lights";
  for (const char* scene : {"showcase", "cornell-dynamic"}) {
    GiRun run(context(), s, scene, 96, 96);
    run.step(2);
    const render::ImageRgba hdr = run.hdr(), indirect = run.indirect(), albedo = run.renderer->readback(render::TargetId::Albedo);
    auto lum = [](const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    size_t lit = 0, bounce = 0;
    for (size_t i = 0; i < hdr.size(); ++i) {
      const glm::vec3 gi = glm::vec3(albedo[i]) * (1.0f - albedo[i].a) * glm::vec3(indirect[i]);
      const double total = lum(glm::vec3(hdr[i])), fromGi = lum(gi);
      if (total <= 1e-4) continue;
      ++lit;
      bounce += fromGi > total - fromGi;
    }
    const double share = double(bounce) / double(lit);
    dyngi::test::report("%s: %.1f%% of the lit pixels get more bounce light than direct light\n", scene, 100 * share);
    if (std::string(scene) == "showcase") {
      EXPECT_GT(share, 0.85);
    }
  }
}
