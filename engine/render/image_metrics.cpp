#include "dyngi/engine/render/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dyngi::render {
namespace {
bool counted(const std::vector<uint8_t>* mask, size_t i) { return !mask || (*mask)[i]; }
double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
}  // namespace

double rmse(const ImageRgba& a, const ImageRgba& ref, const std::vector<uint8_t>* mask) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < std::min(a.size(), ref.size()); ++i) {
    if (!counted(mask, i)) continue;
    for (int c = 0; c < 3; ++c) {
      double d = double(a[i][c]) - ref[i][c];
      sum += d * d;
    }
    n += 3;
  }
  return n ? std::sqrt(sum / double(n)) : 0.0;
}

double relativeMse(const ImageRgba& a, const ImageRgba& ref, const std::vector<uint8_t>* mask) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < std::min(a.size(), ref.size()); ++i) {
    if (!counted(mask, i)) continue;
    for (int c = 0; c < 3; ++c) {
      double d = double(a[i][c]) - ref[i][c];
      sum += d * d / (double(ref[i][c]) * ref[i][c] + 0.01);
    }
    n += 3;
  }
  return n ? sum / double(n) : 0.0;
}

std::vector<double> relativeLuminanceErrors(const ImageRgba& a, const ImageRgba& ref, const std::vector<uint8_t>* mask) {
  auto lum = [](const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  const size_t n = std::min(a.size(), ref.size());
  std::vector<double> errors(n, 0.0);
  double mean = 0;
  size_t counted_ = 0;
  for (size_t i = 0; i < n; ++i)
    if (counted(mask, i)) mean += lum(ref[i]), ++counted_;
  if (counted_ == 0 || !(mean > 0)) return errors;
  const double floor = 0.1 * mean / double(counted_);
  for (size_t i = 0; i < n; ++i)
    if (counted(mask, i)) errors[i] = (lum(a[i]) - lum(ref[i])) / std::max(lum(ref[i]), floor);
  return errors;
}

double relativeLuminanceErrorQuantile(const ImageRgba& a, const ImageRgba& ref, double q, const std::vector<uint8_t>* mask) {
  const std::vector<double> signedErrors = relativeLuminanceErrors(a, ref, mask);
  std::vector<double> errors;
  errors.reserve(signedErrors.size());
  for (size_t i = 0; i < signedErrors.size(); ++i)
    if (counted(mask, i)) errors.push_back(std::abs(signedErrors[i]));
  if (errors.empty()) return 0.0;
  const size_t k = std::min(errors.size() - 1, size_t(std::clamp(q, 0.0, 1.0) * double(errors.size() - 1) + 0.5));
  std::nth_element(errors.begin(), errors.begin() + long(k), errors.end());
  return errors[k];
}

double relativeL1(const ImageRgba& a, const ImageRgba& ref, const std::vector<uint8_t>* mask) {
  double diff = 0, level = 0;
  for (size_t i = 0; i < std::min(a.size(), ref.size()); ++i) {
    if (!counted(mask, i)) continue;
    for (int c = 0; c < 3; ++c) {
      diff += std::abs(double(a[i][c]) - ref[i][c]);
      level += std::abs(double(ref[i][c]));
    }
  }
  if (level == 0.0) return diff == 0.0 ? 0.0 : 1.0;
  return diff / level;
}

double flicker(const std::vector<ImageRgba>& frames) {
  if (frames.size() < 2) return 0.0;
  double sum = 0;
  for (size_t i = 1; i < frames.size(); ++i) sum += relativeL1(frames[i], frames[i - 1]);
  return sum / double(frames.size() - 1);
}

double reprojectedChange(const ImageRgba& current, const ImageRgba& currentPosition, const ImageRgba& previous,
                         const ImageRgba& previousPosition, const glm::mat4& previousViewProj, uint32_t width, uint32_t height,
                         float positionTolerance) {
  const size_t n = size_t(width) * height;
  if (current.size() < n || currentPosition.size() < n || previous.size() < n || previousPosition.size() < n) return 0.0;
  double diff = 0, level = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec4 p = currentPosition[i];
    if (p.w == 0.0f) continue;
    const glm::vec4 clip = previousViewProj * glm::vec4(glm::vec3(p), 1.0f);
    if (clip.w <= 0.0f) continue;
    // Bilinear between the four pixel centres around the point, each tap (with a weight) on the same
    // surface: nearest-pixel resampling alone would change a smooth image by its gradient.
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height)) - 0.5f;
    const glm::vec2 base = glm::floor(pixel), f = pixel - base;
    glm::dvec3 sample(0.0);
    bool usable = true;
    for (int t = 0; t < 4 && usable; ++t) {
      const int dx = t & 1, dy = t >> 1;
      const double weight = double(dx ? f.x : 1.0f - f.x) * double(dy ? f.y : 1.0f - f.y);
      if (weight == 0.0) continue;
      const int qx = int(base.x) + dx, qy = int(base.y) + dy;
      if (qx < 0 || qy < 0 || qx >= int(width) || qy >= int(height)) {
        usable = false;
        break;
      }
      const size_t q = size_t(qy) * width + size_t(qx);
      const glm::vec4 was = previousPosition[q];
      usable = was.w != 0.0f && glm::length(glm::vec3(was) - glm::vec3(p)) <= positionTolerance;
      sample += weight * glm::dvec3(previous[q]);
    }
    if (!usable) continue;
    for (int c = 0; c < 3; ++c) {
      diff += std::abs(double(current[i][c]) - sample[c]);
      level += std::abs(sample[c]);
    }
  }
  if (level == 0.0) return diff == 0.0 ? 0.0 : 1.0;
  return diff / level;
}

size_t settleFrames(const std::vector<ImageRgba>& frames, const ImageRgba& converged, double tolerance) {
  size_t settled = frames.size();
  for (size_t i = frames.size(); i-- > 0;) {
    if (relativeL1(frames[i], converged) > tolerance) break;
    settled = i;
  }
  return settled;
}

double psnr(const ImageRgba& a, const ImageRgba& ref, double peak) {
  if (peak <= 0)
    for (auto& p : ref) peak = std::max({peak, double(p.r), double(p.g), double(p.b)});
  double e = rmse(a, ref);
  if (e == 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(std::max(peak, 1e-12) / e);
}

double ssim(const ImageRgba& a, const ImageRgba& ref, uint32_t w, uint32_t h, double range) {
  if (range <= 0)
    for (auto& p : ref) range = std::max(range, luminance(p));
  range = std::max(range, 1e-12);
  const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
  const uint32_t win = 8, stride = 4;
  double sum = 0;
  int windows = 0;
  for (uint32_t y0 = 0; y0 + win <= h; y0 += stride)
    for (uint32_t x0 = 0; x0 + win <= w; x0 += stride) {
      double ma = 0, mb = 0;
      for (uint32_t y = y0; y < y0 + win; ++y)
        for (uint32_t x = x0; x < x0 + win; ++x) ma += luminance(a[size_t(y) * w + x]), mb += luminance(ref[size_t(y) * w + x]);
      const double n = win * win;
      ma /= n, mb /= n;
      double va = 0, vb = 0, cov = 0;
      for (uint32_t y = y0; y < y0 + win; ++y)
        for (uint32_t x = x0; x < x0 + win; ++x) {
          double da = luminance(a[size_t(y) * w + x]) - ma, db = luminance(ref[size_t(y) * w + x]) - mb;
          va += da * da, vb += db * db, cov += da * db;
        }
      va /= n - 1, vb /= n - 1, cov /= n - 1;
      sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  return windows ? sum / windows : 1.0;
}

glm::dvec3 meanOver(const ImageRgba& a, const std::vector<uint8_t>* mask) {
  glm::dvec3 s(0.0);
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (counted(mask, i)) s += glm::dvec3(a[i]), ++n;
  return n ? s / double(n) : s;
}

std::vector<uint8_t> tonemapToSrgb8(const ImageRgba& hdr, float exposure, int toneMapper) {
  std::vector<uint8_t> out(hdr.size() * 4);
  auto aces = [](float x) { return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f); };
  auto srgb = [](float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  };
  for (size_t i = 0; i < hdr.size(); ++i) {
    glm::vec3 c = glm::vec3(hdr[i]) * exposure;
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) c = {1, 0, 1};
    for (int k = 0; k < 3; ++k) {
      float v = toneMapper == 0 ? aces(c[k]) : std::clamp(c[k], 0.0f, 1.0f);
      out[i * 4 + size_t(k)] = uint8_t(std::lround(srgb(v) * 255.0f));
    }
    out[i * 4 + 3] = 255;
  }
  return out;
}

}  // namespace dyngi::render
