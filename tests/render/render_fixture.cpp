#include "render/render_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "dyngi/engine/ecs/scheduler.h"
#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/scene/transform_system.h"

namespace dyngi::test {

namespace {
// The process's one context (each render test runs in its own process under ctest). A gtest
// environment destroys it after the last test and then counts the validation errors raised while it
// went down (objects left undestroyed, leaks), which a test's own TearDown cannot see.
std::unique_ptr<render::VulkanContext>& contextSlot() {
  static std::unique_ptr<render::VulkanContext> ctx;
  return ctx;
}

class ContextTeardownCheck final : public ::testing::Environment {
 public:
  void TearDown() override {
    const uint32_t before = render::VulkanContext::processValidationErrorCount();
    contextSlot().reset();
    EXPECT_EQ(render::VulkanContext::processValidationErrorCount(), before)
        << "Vulkan validation reported errors while the device was destroyed (see stderr)";
  }
};
[[maybe_unused]] ::testing::Environment* const kTeardownCheck = ::testing::AddGlobalTestEnvironment(new ContextTeardownCheck);
}  // namespace

render::VulkanContext& RenderTest::context() {
  auto& ctx = contextSlot();
  if (!ctx) {
    render::ContextOptions o;
    o.validation = true;
    o.requireValidation = true;  // a test run without the layer would check nothing: fail instead
    // The layer's synchronization checks (hazards between passes) too: on lavapipe they cost about 2% of
    // the suite's time. DYNGI_SYNC_VALIDATION=0 turns them off to tell a hazard from another error.
    const char* sync = std::getenv("DYNGI_SYNC_VALIDATION");
    o.synchronizationValidation = !(sync && std::string(sync) == "0");
    o.quiet = true;
    ctx = std::make_unique<render::VulkanContext>(o);
  }
  return *ctx;
}

void RenderTest::TearDown() {
  EXPECT_EQ(context().validationErrorCount(), 0u) << "Vulkan validation reported errors (see stderr)";
}

Frame RenderTest::render(ecs::World& world, scene::AssetStore& assets, uint32_t width, uint32_t height,
                         const render::RendererSettings& settings, int frames) {
  render::Renderer renderer(context(), settings);
  EXPECT_TRUE(renderer.resize(width, height));
  ecs::Scheduler scheduler;
  scheduler.add(ecs::Phase::PostUpdate, std::make_unique<scene::TransformSystem>());
  Frame f;
  for (int i = 0; i < frames; ++i) {
    scheduler.runFrame(world, ecs::FrameTime{1.0 / 60.0, double(i) / 60.0, uint64_t(i)});
    f.snapshot = render::extractSnapshot(world, assets, uint64_t(i));
    renderer.render(f.snapshot);
  }
  f.width = width;
  f.height = height;
  f.hdr = renderer.readback(render::TargetId::Hdr);
  f.position = renderer.readback(render::TargetId::Position);
  f.normal = renderer.readback(render::TargetId::Normal);
  f.albedo = renderer.readback(render::TargetId::Albedo);
  f.ldr = renderer.readbackLdr();
  return f;
}

bool segmentHitsBox(const glm::vec3& a, const glm::vec3& b, const Obb& box, float margin) {
  // Slab test in the box's local frame (the model has no scale in our scenes' boxes).
  glm::mat4 inv = glm::inverse(box.model);
  glm::vec3 la = glm::vec3(inv * glm::vec4(a, 1.0f)), lb = glm::vec3(inv * glm::vec4(b, 1.0f));
  glm::vec3 d = lb - la, h = box.halfExtent + glm::vec3(margin);
  float t0 = 1e-4f, t1 = 1.0f - 1e-4f;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12f) {
      if (la[i] < -h[i] || la[i] > h[i]) return false;
      continue;
    }
    float ta = (-h[i] - la[i]) / d[i], tb = (h[i] - la[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

void dumpTestImage(const std::string& name, const std::vector<glm::vec4>& img, uint32_t w, uint32_t h) {
  const char* dir = std::getenv("DYNGI_TEST_IMAGES");
  if (!dir) return;
  render::writeExr(std::string(dir) + "/" + name + ".exr", w, h, img);
  std::vector<uint8_t> px(size_t(w) * h * 4, 255);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < 3; ++c) px[i * 4 + c] = uint8_t(std::lround(255.0 * std::pow(std::clamp(double(img[i][c]) * 2.0, 0.0, 1.0), 1.0 / 2.2)));
  render::writePng(std::string(dir) + "/" + name + ".png", w, h, px);
}

}  // namespace dyngi::test
