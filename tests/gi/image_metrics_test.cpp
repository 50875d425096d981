#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "dyngi/engine/render/image_metrics.h"

using namespace dyngi::render;

TEST(ImageMetrics, IdenticalImages) {
  ImageRgba a(64 * 64);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> U(0.0f, 2.0f);
  for (auto& p : a) p = glm::vec4(U(rng), U(rng), U(rng), 1);
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_EQ(relativeMse(a, a), 0.0);
  EXPECT_TRUE(std::isinf(psnr(a, a)));
  EXPECT_NEAR(ssim(a, a, 64, 64), 1.0, 1e-12);
}

TEST(ImageMetrics, KnownDifferences) {
  ImageRgba ref(100, glm::vec4(1.0f)), a(100, glm::vec4(1.5f));
  EXPECT_NEAR(rmse(a, ref), 0.5, 1e-12);
  EXPECT_NEAR(relativeMse(a, ref), 0.25 / 1.01, 1e-6);
  EXPECT_NEAR(psnr(a, ref), 20.0 * std::log10(1.0 / 0.5), 1e-9);
  std::vector<uint8_t> mask(100, 0);
  mask[3] = 1;
  a[3] = glm::vec4(4, 5, 6, 1);
  glm::dvec3 m = meanOver(a, &mask);
  EXPECT_EQ(m, glm::dvec3(4, 5, 6));
  // Noise lowers SSIM; more noise lowers it more.
  ImageRgba base(64 * 64), n1(64 * 64), n2(64 * 64);
  std::mt19937 rng(2);
  std::normal_distribution<float> N(0.0f, 1.0f);
  for (size_t i = 0; i < base.size(); ++i) {
    float v = 0.5f + 0.4f * std::sin(float(i % 64) * 0.2f);
    base[i] = glm::vec4(v, v, v, 1);
    float e = N(rng);
    n1[i] = base[i] + glm::vec4(0.02f * e, 0.02f * e, 0.02f * e, 0);
    n2[i] = base[i] + glm::vec4(0.2f * e, 0.2f * e, 0.2f * e, 0);
  }
  double s1 = ssim(n1, base, 64, 64), s2 = ssim(n2, base, 64, 64);
  EXPECT_LT(s1, 1.0);
  EXPECT_LT(s2, s1);
}

TEST(ImageMetrics, CpuTonemapEncodesSrgb) {
  ImageRgba hdr = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 1, 1, 1), glm::vec4(0.5f, 0.0031308f, 100.0f, 1)};
  auto ldr = tonemapToSrgb8(hdr, 1.0f, 1);  // clamp operator: pure sRGB encoding
  EXPECT_EQ(ldr[0], 0);
  EXPECT_EQ(ldr[4], 255);
  EXPECT_EQ(ldr[8], uint8_t(std::lround((1.055 * std::pow(0.5, 1 / 2.4) - 0.055) * 255)));
  EXPECT_EQ(ldr[10], 255);
}

// The quality metrics on sequences whose answers are known by construction.
TEST(ImageMetrics, FlickerAndSettleOnKnownSequences) {
  auto flat = [](float v) { return ImageRgba(16, glm::vec4(v, v, v, 1.0f)); };
  EXPECT_DOUBLE_EQ(relativeL1(flat(1.1f), flat(1.0f)), double(1.1f - 1.0f) / 1.0);
  EXPECT_EQ(relativeL1(flat(0.0f), flat(0.0f)), 0.0);
  EXPECT_EQ(relativeL1(flat(0.5f), flat(0.0f)), 1.0);
  // Alternating 1.0 / 1.02: every step changes by 0.02 relative to the previous frame's level.
  std::vector<ImageRgba> alternating;
  for (int i = 0; i < 10; ++i) alternating.push_back(flat(i % 2 ? 1.02f : 1.0f));
  EXPECT_NEAR(flicker(alternating), (0.02 / 1.0 + 0.02 / 1.02) / 2.0, 1e-3);
  EXPECT_EQ(flicker({flat(1.0f), flat(1.0f), flat(1.0f)}), 0.0);
  // Approaching 1 as 1 - 0.5^k: within 5 percent from k = 5 on (0.5^5 = 0.031), not at k = 4 (0.0625).
  std::vector<ImageRgba> approach;
  for (int k = 1; k <= 12; ++k) approach.push_back(flat(1.0f - std::pow(0.5f, float(k))));
  EXPECT_EQ(settleFrames(approach, flat(1.0f), 0.05), 4u);  // index of k = 5
  // A late excursion counts: it has not settled until after the last frame out of tolerance.
  approach[9] = flat(0.5f);
  EXPECT_EQ(settleFrames(approach, flat(1.0f), 0.05), 10u);
  approach.back() = flat(0.5f);
  EXPECT_EQ(settleFrames(approach, flat(1.0f), 0.05), approach.size()) << "never settles";
}

// A camera that moved one pixel to the right over a plane: every pixel's point is found one pixel to
// the right in the previous frame (orthographic, so exactly), the last column was off screen, and a
// pixel whose previous position shows another point (disoccluded) is left out.
TEST(ImageMetrics, ReprojectedChangeFollowsTheSurfaceNotThePixel) {
  constexpr uint32_t W = 8, H = 6;
  // Previous camera: world x in [0, 8] and y in [0, 6] onto the image (z = 0 plane).
  const glm::mat4 previousViewProj = glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, -1.0f, 0.0f)) *
                                     glm::scale(glm::mat4(1.0f), glm::vec3(2.0f / W, 2.0f / H, 1.0f));
  auto shade = [](glm::vec3 p) { return glm::vec4(0.1f + p.x, 0.5f + 0.1f * p.y, 1.0f, 1.0f); };  // a function of the surface point
  ImageRgba prevPos(W * H), prev(W * H), curPos(W * H), cur(W * H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + x;
      const float fx = float(x), fy = float(y);
      prevPos[i] = glm::vec4(fx + 0.5f, fy + 0.5f, 0.0f, 1.0f);
      curPos[i] = glm::vec4(fx + 1.5f, fy + 0.5f, 0.0f, 1.0f);  // the view moved one pixel to the right
      prev[i] = shade(glm::vec3(prevPos[i]));
      cur[i] = shade(glm::vec3(curPos[i]));
    }
  EXPECT_NEAR(reprojectedChange(cur, curPos, prev, prevPos, previousViewProj, W, H, 1e-3f), 0.0, 1e-7);
  EXPECT_GT(relativeL1(cur, prev), 0.1) << "pixel by pixel the frames differ: only the reprojection sees the same surface";
  // 10 percent brighter everywhere: a change of 0.1.
  ImageRgba brighter = cur;
  for (auto& p : brighter) p *= 1.1f;
  EXPECT_NEAR(reprojectedChange(brighter, curPos, prev, prevPos, previousViewProj, W, H, 1e-3f), 0.1, 1e-6);
  // A pixel whose previous sample shows another point (an occluder was there) does not count.
  ImageRgba occluded = prevPos;
  occluded[2 * W + 4] = glm::vec4(4.5f, 2.5f, -1.0f, 1.0f);
  ImageRgba changedThere = cur;
  changedThere[2 * W + 3] = glm::vec4(100.0f);  // the current pixel that maps onto it
  EXPECT_NEAR(reprojectedChange(changedThere, curPos, prev, occluded, previousViewProj, W, H, 1e-3f), 0.0, 1e-7);
  EXPECT_GT(reprojectedChange(changedThere, curPos, prev, prevPos, previousViewProj, W, H, 1e-3f), 1.0);
}

// The error's tail: 98 pixels right and two 3x too bright is a 99th percentile of 2 (the 99th of the 100
// sorted errors) and a 97th of 0; a dark reference pixel counts against a tenth of the mean.
TEST(ImageMetrics, RelativeLuminanceErrorQuantileReadsTheTail) {
  ImageRgba ref(100, glm::vec4(1.0f)), a = ref;
  a[42] = a[43] = glm::vec4(3.0f);
  EXPECT_NEAR(relativeLuminanceErrorQuantile(a, ref, 0.97), 0.0, 1e-12);
  EXPECT_NEAR(relativeLuminanceErrorQuantile(a, ref, 0.99), 2.0, 1e-12);
  EXPECT_NEAR(relativeLuminanceErrorQuantile(a, ref, 1.0), 2.0, 1e-12);
  ImageRgba dark = ref, b = ref;
  dark[7] = glm::vec4(0.0f);  // mean 0.99: its floor is 0.099
  b[7] = glm::vec4(0.099f);
  EXPECT_NEAR(relativeLuminanceErrorQuantile(b, dark, 1.0), 1.0, 1e-6);
  EXPECT_EQ(relativeLuminanceErrorQuantile(a, ImageRgba(100, glm::vec4(0.0f)), 0.99), 0.0);
  // Per pixel and signed (the error map's input): +2 where 3x too bright, -1 where black, 0 elsewhere.
  ImageRgba c = a;
  c[5] = glm::vec4(0.0f);
  const std::vector<double> e = relativeLuminanceErrors(c, ref);
  EXPECT_NEAR(e[42], 2.0, 1e-12);
  EXPECT_NEAR(e[5], -1.0, 1e-12);
  EXPECT_EQ(e[0], 0.0);
}
