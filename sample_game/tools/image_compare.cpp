// dyngi_imgcmp: compares two linear EXR images (same size) with dyngi's image metrics.
// usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr   -> one JSON line on stdout; exit 2 on bad input
#include <cstdio>

#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/image_metrics.h"

int main(int argc, char** argv) {
  using namespace dyngi::render;
  if (argc != 3) {
    std::fprintf(stderr, "usage: dyngi_imgcmp REFERENCE.exr IMAGE.exr\n");
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
  glm::dvec3 a = meanOver(img), b = meanOver(ref);
  double la = 0.2126 * a.r + 0.7152 * a.g + 0.0722 * a.b, lb = 0.2126 * b.r + 0.7152 * b.g + 0.0722 * b.b;
  std::printf("{\"rmse\": %.6f, \"rel_mse\": %.6f, \"psnr\": %.3f, \"ssim\": %.5f, \"mean_ratio\": %.5f, \"p99_rel_lum\": %.5f}\n",
              rmse(img, ref), relativeMse(img, ref), psnr(img, ref), ssim(img, ref, w0, h0), lb > 0 ? la / lb : 0.0,
              relativeLuminanceErrorQuantile(img, ref, 0.99));
  return 0;
}
