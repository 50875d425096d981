// The reduced screen's uniforms (gi_module/indirect/reduced_screen.h) against the full frame's: reduced
// pixel q's ray is the full frame's through the point (q + 0.5) x full size / reduced size, a point on
// that ray projects to q's centre, and the pixel the reduction samples there lies within half a
// full-resolution pixel of it.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/engine/render/frame_uniforms.h"
#include "indirect/reduced_screen.h"

using namespace dyngi;

namespace {
// The ray through continuous pixel coordinate c (pixel i spans [i, i + 1)).
glm::vec3 rayAt(const gpu::FrameUniforms& u, glm::vec2 c) {
  return glm::vec3(u.pixelRay0) + (c.x - 0.5f) * glm::vec3(u.pixelRayStepX) + (c.y - 0.5f) * glm::vec3(u.pixelRayStepY);
}
// Where a world point lands in u's continuous pixel coordinates.
glm::vec2 project(const gpu::FrameUniforms& u, glm::vec3 p) {
  const glm::vec4 clip = u.viewProj * glm::vec4(p, 1.0f);
  return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(u.sizeAndCount);
}
}  // namespace

TEST(ReducedScreen, AReducedPixelSeesWhatTheFullFrameSeesAtItsCentre) {
  render::CameraView camera;
  camera.position = {0.3f, 1.1f, 3.7f};
  camera.view = glm::lookAt(camera.position, glm::vec3(-0.2f, 0.8f, 0.0f), glm::vec3(0, 1, 0));
  camera.yfov = 0.9f;
  for (glm::uvec2 size : {glm::uvec2(256, 256), glm::uvec2(255, 131), glm::uvec2(768, 432)})
    for (float s : {1.0f, 1.18f, 1.5f, 2.0f, 3.0f, 4.0f}) {
      SCOPED_TRACE(testing::Message() << size.x << "x" << size.y << " at scale " << s);
      gpu::FrameUniforms full = render::cameraUniforms(camera, size.x, size.y);
      full.sizeAndCount = glm::uvec4(size, 3u, 7u);
      const gpu::FrameUniforms low = gi::reducedUniforms(full, s);
      const uint32_t w = gi::ReducedScreen::reducedSize(size.x, s), h = gi::ReducedScreen::reducedSize(size.y, s);
      ASSERT_EQ(low.sizeAndCount, glm::uvec4(w, h, 3u, 7u));
      EXPECT_EQ(w, uint32_t(std::lround(double(size.x) / s)));
      EXPECT_EQ(low.cameraPos, full.cameraPos);
      EXPECT_EQ(low.viewProj, full.viewProj) << "in NDC both screens are the same";
      const glm::vec2 scale = glm::vec2(float(double(size.x) / w), float(double(size.y) / h));
      double worstRay = 0.0, worstPixel = 0.0, worstSample = 0.0;
      for (uint32_t qy = 0; qy < h; qy += 7)
        for (uint32_t qx = 0; qx < w; qx += 5) {
          const glm::vec2 q = glm::vec2(float(qx), float(qy)), centre = (q + 0.5f) * scale;  // full-resolution coordinates
          const glm::vec3 r = rayAt(full, centre);
          worstRay = std::max(worstRay, double(glm::length(rayAt(low, q + 0.5f) - r) / glm::length(r)));
          for (float t : {0.5f, 2.0f, 9.0f}) {
            const glm::vec3 p = glm::vec3(full.cameraPos) + t * r;
            worstPixel = std::max(worstPixel, double(glm::length(project(full, p) - centre)));  // the full frame agrees with itself
            worstPixel = std::max(worstPixel, double(glm::length(project(low, p) - (q + 0.5f)) * s));
          }
          // The pixel reduce_gbuffer.comp samples for q: its centre within half a pixel of q's centre.
          const glm::vec2 sampled = glm::min(glm::floor(centre), glm::vec2(size) - 1.0f) + 0.5f;
          worstSample = std::max(worstSample, double(glm::max(glm::abs(sampled.x - centre.x), glm::abs(sampled.y - centre.y))));
        }
      EXPECT_LT(worstRay, 1e-5);
      EXPECT_LT(worstPixel, 2e-3) << "a point on a reduced pixel's ray projects to that pixel's centre (in full-resolution pixels)";
      EXPECT_LE(worstSample, 0.5 + 1e-4);
      if (s == 1.0f) {
        EXPECT_EQ(w, size.x);
        EXPECT_EQ(low.pixelRay0, full.pixelRay0) << "scale 1 leaves the frame as it is";
      }
    }
}
