#pragma once
// Shared set-up for rendering tests: one Vulkan context per test process (validation and its
// synchronization checks on, required; errors counted through device destruction), helpers to
// render a world and read every target back, and a CPU ray/box test used as independent shadow truth.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "dyngi/engine/ecs/world.h"
#include "dyngi/engine/render/renderer.h"
#include "dyngi/engine/scene/assets.h"
#include "dyngi/engine/scene/components.h"

namespace dyngi::test {

struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> hdr, position, normal, albedo;
  std::vector<uint8_t> ldr;
  render::RenderSnapshot snapshot;
  const glm::vec4& at(const std::vector<glm::vec4>& img, uint32_t x, uint32_t y) const { return img[size_t(y) * width + x]; }
};

class RenderTest : public ::testing::Test {
 protected:
  static render::VulkanContext& context();
  void TearDown() override;

  // Propagates transforms, extracts and renders `frames` frames, reads everything back.
  Frame render(ecs::World& world, scene::AssetStore& assets, uint32_t width, uint32_t height,
               const render::RendererSettings& settings = {}, int frames = 1);
};

// DYNGI_TEST_IMAGES=dir: tests write the images they compare there as EXR and PNG (x2, gamma 2.2), for
// a person to look at; without it nothing is written.
void dumpTestImage(const std::string& name, const std::vector<glm::vec4>& img, uint32_t width, uint32_t height);

// An oriented box (unit cube scaled by halfExtent, then `model`), for CPU visibility checks.
struct Obb {
  glm::mat4 model;
  glm::vec3 halfExtent;
};
// True when the open segment a->b passes within `margin` of the box (margin < 0 shrinks it).
bool segmentHitsBox(const glm::vec3& a, const glm::vec3& b, const Obb& box, float margin);

}  // namespace dyngi::test
