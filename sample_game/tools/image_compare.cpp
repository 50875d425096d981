// dyngi_imgcmp: compares two linear EXR images (same size) with dyngi's image metrics.
// usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr [--error-map FILE.png] [--region X,Y,W,H]...
//   -> one JSON line on stdout; exit 2 on bad input. Each --region (pixels, y down) adds the two images'
//   mean luminance over that rectangle and their ratio: a region mean shows a bias that the whole image's
//   mean hides, and averages the reference's noise away. The error map shows where the p99_rel_lum tail lies:
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
  const char* usage = "usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr [--error-map FILE.png] [--region X,Y,W,H]...\n";
  if (argc < 3) {
    std::fprintf(stderr, "%s", usage);
    return 2;
  }
  const char* mapPath = nullptr;
  struct Rect {
    int x, y, w, h;
  };
  std::vector<Rect> regions;
  for (int i = 3; i < argc; i += 2) {
    Rect r{};
    if (i + 1 < argc && std::strcmp(argv[i], "--error-map") == 0) {
      mapPath = argv[i + 1];
    } else if (i + 1 < argc && std::strcmp(argv[i], "--region") == 0 &&
               std::sscanf(argv[i + 1], "%d,%d,%d,%d", &r.x, &r.y, &r.w, &r.h) == 4 && r.x >= 0 && r.y >= 0 && r.w > 0 && r.h > 0) {
      regions.push_back(r);
    } else {
      std::fprintf(stderr, "dyngi_imgcmp: bad argument '%s'\n%s", argv[i], usage);
      return 2;
    }
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
  for (const Rect& r : regions)
    if (uint32_t(r.x + r.w) > w0 || uint32_t(r.y + r.h) > h0) {
      std::fprintf(stderr, "dyngi_imgcmp: region %d,%d,%d,%d outside the %ux%u image\n", r.x, r.y, r.w, r.h, w0, h0);
      return 2;
    }
  auto lum = [](const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  if (mapPath) {
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
    err = writePng(mapPath, w0, h0, rgba);
    if (!err.empty()) {
      std::fprintf(stderr, "dyngi_imgcmp: %s\n", err.c_str());
      return 2;
    }
  }
  glm::dvec3 a = meanOver(img), b = meanOver(ref);
  double la = 0.2126 * a.r + 0.7152 * a.g + 0.0722 * a.b, lb = 0.2126 * b.r + 0.7152 * b.g + 0.0722 * b.b;
  // JSON has no infinity: the PSNR of two equal images is written as null.
  const double peak = psnr(img, ref);
  const std::string psnrText = std::isfinite(peak) ? std::to_string(peak) : "null";
  std::printf("{\"rmse\": %.6f, \"rel_mse\": %.6f, \"psnr\": %s, \"ssim\": %.5f, \"mean_ratio\": %.5f, \"p99_rel_lum\": %.5f",
              rmse(img, ref), relativeMse(img, ref), psnrText.c_str(), ssim(img, ref, w0, h0), lb > 0 ? la / lb : 0.0,
              relativeLuminanceErrorQuantile(img, ref, 0.99));
  if (!regions.empty()) {
    std::printf(", \"regions\": [");
    for (size_t k = 0; k < regions.size(); ++k) {
      const Rect& r = regions[k];
      double sumRef = 0, sumImg = 0;
      for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x) {
          sumRef += lum(ref[size_t(y) * w0 + size_t(x)]);
          sumImg += lum(img[size_t(y) * w0 + size_t(x)]);
        }
      const double n = double(r.w) * r.h;
      std::printf("%s{\"rect\": [%d, %d, %d, %d], \"reference\": %.6f, \"image\": %.6f, \"ratio\": %.4f}", k ? ", " : "", r.x, r.y, r.w, r.h,
                  sumRef / n, sumImg / n, sumRef > 0 ? sumImg / sumRef : 0.0);
    }
    std::printf("]");
  }
  std::printf("}\n");
  return 0;
}
