// The third-party glTF scenes (../shared/scenes) import and render with sensible numbers.
#include <gtest/gtest.h>

#include "support/shared_scenes.h"

#include <filesystem>

#include "dyngi/engine/scene/gltf_import.h"
#include "render/render_fixture.h"
#include "scenes/builtin_scenes.h"

using namespace dyngi;
using namespace dyngi::test;

TEST_F(RenderTest, SharedCornellBoxShowsItsEmitter) {
  DYNGI_SHARED_SCENE_OR_SKIP(path, "CornellBox.glb");
  ecs::World w;
  scene::AssetStore assets;
  ASSERT_EQ(scene::importGltf(path, w, assets), "");
  EXPECT_FALSE(sample::addDefaultLightIfUnlit(w)) << "the emitter is its light";
  Frame f = render(w, assets, 128, 128);
  int covered = 0, emitting = 0;
  for (size_t i = 0; i < f.hdr.size(); ++i) {
    covered += f.position[i].w > 0.5f;
    if (f.hdr[i].r > 1.0f) {
      ++emitting;
      EXPECT_NEAR(f.hdr[i].r, 100.0f, 0.5f) << "emissive factor 1 x KHR_materials_emissive_strength 100";
    }
  }
  EXPECT_GT(covered, 128 * 128 / 4);
  EXPECT_GT(emitting, 8);
}

TEST_F(RenderTest, SharedUnlitScenesGetADefaultLight) {
  for (const char* name : {"Fox.glb", "IrradianceVolumeExample.glb"}) {
    DYNGI_SHARED_SCENE_OR_SKIP(path, name);
    ecs::World w;
    scene::AssetStore assets;
    ASSERT_EQ(scene::importGltf(path, w, assets), "") << name;
    EXPECT_TRUE(sample::addDefaultLightIfUnlit(w)) << name;
    Frame f = render(w, assets, 128, 128);
    int covered = 0, lit = 0;
    for (size_t i = 0; i < f.hdr.size(); ++i) {
      if (f.position[i].w < 0.5f) continue;
      ++covered;
      lit += f.hdr[i].r + f.hdr[i].g + f.hdr[i].b > 1e-3f;
    }
    EXPECT_GT(covered, 128 * 128 / 40) << name << ": the auto-framed camera sees the model";
    EXPECT_GT(lit, covered / 3) << name << ": a good part of it is lit";
  }
}
