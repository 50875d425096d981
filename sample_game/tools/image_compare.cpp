// dyngi_imgcmp: compares two linear EXR images (same size) with dyngi's image metrics.
// usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr [--error-map FILE.png]
//   -> one JSON line on stdout; exit 2 on bad input. The error map shows where the p99_rel_lum tail lies:
//   red where IMAGE is brighter, blue where darker, full at a relative luminance error of 1 (the same
//   measure as p99_rel_lum, render::relativeLuminanceErrors), over a grey that shows the reference itself.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/image_metrics.h"

int main(int argc, char** argv) {
  using namespace dyngi::render;
  const bool withMap = argc == 5 && std::strcmp(argv[3], "--error-map") == 0;
  if (argc != 3 && !withMap) {
    std::fprintf(stderr, "usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr [--error-map FILE.png]\n");
    return 2;
  }
  uint32_t w0, h0, w1, h1;
  ImageRgba ref, img;
  std::string err = readExr(argv[1], w0, h0, ref);
  if (err.empty()) err = readExr(argv[2], w1, h1, img);
  if (!err.empty()) {
    std::fprintf(stderr, "dyngi_imgcmp: %s\n", err.c_str());
    return 2;
  }
  if (w0 != w1 || h0 != h1) {
    std::fprintf(stderr, "dyngi_imgcmp: sizes differ (%ux%u vs %ux%u)\n", w0, h0, w1, h1);
    return 2;
  }
  auto lum = [](const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  if (withMap) {
    const std::vector<double> errors = relativeLuminanceErrors(img, ref);
    double refMax = 0;
    for (const glm::vec4& c : ref) refMax = std::max(refMax, lum(c));
    std::vector<uint8_t> rgba(ref.size() * 4);
    for (size_t i = 0; i < ref.size(); ++i) {
      const double e = errors[i];
      const double m = std::min(1.0, std::abs(e));
      // The reference's own brightness as the grey underneath (square root, so dim walls still show).
      const double base = 0.25 + 0.5 * (refMax > 0 ? std::sqrt(std::max(0.0, lum(ref[i]) / refMax)) : 0.0);
      uint8_t grey = uint8_t(std::clamp(base * 255.0 * (1.0 - m), 0.0, 255.0));
      uint8_t hot = uint8_t(std::clamp(255.0 * m + grey, 0.0, 255.0));
      rgba[i * 4 + 0] = e > 0 ? hot : grey;
      rgba[i * 4 + 1] = grey;
      rgba[i * 4 + 2] = e < 0 ? hot : grey;
      rgba[i * 4 + 3] = 255;
    }
    err = writePng(argv[4], w0, h0, rgba);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_imgcmp: %s\n", err.c_str());
      return 2;
    }
  }
  glm::dvec3 a = meanOver(img), b = meanOver(ref);
  double la = 0.2126 * a.r + 0.7152 * a.g + 0.0722 * a.b, lb = 0.2126 * b.r + 0.7152 * b.g + 0.0722 * b.b;
  std::printf("{\"rmse\": %.6f, \"rel_mse\": %.6f, \"psnr\": %.3f, \"ssim\": %.5f, \"mean_ratio\": %.5f, \"p99_rel_lum\": %.5f}\n",
              rmse(img, ref), relativeMse(img, ref), psnr(img, ref), ssim(img, ref, w0, h0), lb > 0 ? la / lb : 0.0,
              relativeLuminanceErrorQuantile(img, ref, 0.99));
  return 0;
}
