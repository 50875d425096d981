// The pixel rays in FrameUniforms against the projection they come from: a world point projected to
// its (continuous) pixel coordinate must come back from its view depth along that pixel's ray.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/engine/render/frame_uniforms.h"

namespace dyngi::render {
namespace {

TEST(FrameUniformsTest, PixelRaysReconstructWorldPositionsFromViewDepth) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const std::pair<uint32_t, uint32_t> sizes[] = {{512, 512}, {1280, 720}, {333, 517}, {1, 1}};
  for (auto [width, height] : sizes)
    for (int c = 0; c < 8; ++c) {
      CameraView cam;
      cam.position = glm::vec3(u(rng), u(rng), u(rng)) * 5.0f;
      glm::vec3 target = cam.position + glm::normalize(glm::vec3(u(rng), u(rng) * 0.5f, u(rng)) + glm::vec3(0.0f, 0.0f, 0.01f));
      cam.view = glm::lookAtRH(cam.position, target, glm::vec3(0, 1, 0));
      cam.yfov = 0.4f + 0.8f * (u(rng) + 1.0f);
      cam.znear = 0.05f;
      cam.zfar = 100.0f;
      gpu::FrameUniforms fu = cameraUniforms(cam, width, height);
      EXPECT_NEAR(glm::length(glm::vec3(fu.viewForward)), 1.0f, 1e-6f);
      for (int i = 0; i < 200; ++i) {
        // A point inside the view frustum.
        glm::vec4 ndc(u(rng) * 0.98f, u(rng) * 0.98f, 0.2f + 0.79f * (u(rng) + 1.0f) * 0.5f, 1.0f);
        glm::vec4 h = fu.invViewProj * ndc;
        glm::vec3 p = glm::vec3(h) / h.w;
        glm::vec4 clip = fu.viewProj * glm::vec4(p, 1.0f);
        glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);  // continuous
        float depth = glm::dot(p - cam.position, glm::vec3(fu.viewForward));
        ASSERT_GT(depth, 0.0f);
        glm::vec3 ray = glm::vec3(fu.pixelRay0) + (pixel.x - 0.5f) * glm::vec3(fu.pixelRayStepX) + (pixel.y - 0.5f) * glm::vec3(fu.pixelRayStepY);
        glm::vec3 back = cam.position + depth * ray;
        float d = glm::length(p - cam.position);
        ASSERT_LT(glm::length(back - p), 1e-4f * d) << width << "x" << height << " camera " << c << " point " << i;
      }
    }
}

}  // namespace
}  // namespace dyngi::render
