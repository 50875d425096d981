#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
