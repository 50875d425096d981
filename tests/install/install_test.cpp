// The drop-in subsystem end to end: scripts/test_install.sh installs dyngi to a fresh prefix, builds
// examples/minimal_host against that prefix with a clean CMake configure, and runs it on
// assets/cornell_box.gltf. The image it writes must be lit, and lit by the GI: the ceiling is outside the
// spot's cone (it points down), so only bounce light reaches it.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "support/sample_run.h"
#include "support/temp_dir.h"

using namespace dyngi::test;

namespace {

struct PngFigures {
  int width = 0, height = 0;
  double mean = 0;          // 0..255, all pixels
  double clipped = 0;       // fraction of pixels at white
  double ceilingMean = 0;   // the ceiling's band (rows 4-10 percent, middle half of the columns)
};

PngFigures measure(const std::string& path) {
  PngFigures f;
  int n = 0;
  unsigned char* png = stbi_load(path.c_str(), &f.width, &f.height, &n, 3);
  if (!png) return f;
  double sum = 0, clipped = 0, ceiling = 0, ceilingPixels = 0;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const unsigned char* p = png + 3 * (size_t(y) * size_t(f.width) + size_t(x));
      const double v = (p[0] + p[1] + p[2]) / 3.0;
      sum += v;
      clipped += p[0] >= 250 && p[1] >= 250 && p[2] >= 250;
      if (y > f.height * 4 / 100 && y < f.height * 10 / 100 && x > f.width / 4 && x < f.width * 3 / 4) ceiling += v, ++ceilingPixels;
    }
  stbi_image_free(png);
  const double pixels = double(f.width) * f.height;
  f.mean = sum / pixels;
  f.clipped = clipped / pixels;
  f.ceilingMean = ceilingPixels > 0 ? ceiling / ceilingPixels : 0;
  return f;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// scripts/test_install.sh into OUT (a fresh directory): install, configure, build, run for `frames`.
SampleRun installAndRun(const TempDir& dir, const std::string& out, int frames) {
  std::string args = quoted(DYNGI_BUILD_DIR);
  args += ' ';
  args += quoted(out);
  args += ' ';
  args += std::to_string(frames);
  return runSample("bash " DYNGI_SOURCE_DIR "/scripts/test_install.sh", args, dir, 600);
}

}  // namespace

TEST(Install, MinimalHostBuiltAgainstTheInstalledPackageRendersBounceLight) {
  TempDir dir;
  const SampleRun run = installAndRun(dir, dir.file("out"), 16);
  ASSERT_EQ(run.exitCode, 0) << run.err << "\n(logs: install.log, configure.log, build.log in the temporary directory)";
  const PngFigures f = measure(dir.file("out/minimal_host.png"));
  std::printf("minimal_host.png: %dx%d, mean %.1f, clipped %.2f%%, ceiling %.1f\n", f.width, f.height, f.mean, 100 * f.clipped,
              f.ceilingMean);
  ASSERT_EQ(f.width, 512) << "a decodable 512x512 PNG";
  EXPECT_GT(f.mean, 10.0) << "not black";
  EXPECT_LT(f.mean, 200.0) << "not washed out";
  EXPECT_LT(f.clipped, 0.05) << "not saturated";
  // With --gi off the ceiling band is black (mean 0.0): its light is the GI's.
  EXPECT_GT(f.ceilingMean, 15.0) << "the ceiling gets bounce light";
}

// The example handles bad input as the sample does: one line, exit 2.
TEST(Install, MinimalHostRefusesBadInputWithOneLine) {
  TempDir dir;
  const std::string host = dir.file("out/host-build/minimal_host");
  const SampleRun built = installAndRun(dir, dir.file("out"), 1);
  ASSERT_EQ(built.exitCode, 0) << built.err;
  const std::string scene = quoted(DYNGI_SOURCE_DIR "/assets/cornell_box.gltf"), png = quoted(dir.file("x.png"));
  const std::string cases[] = {"/nonexistent.gltf " + png, scene + " " + png + " 4 no_such_technique", scene + " " + png + " -3", ""};
  for (const std::string& args : cases) {
    const SampleRun r = runSample(host, args, dir, 120);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

namespace {
// dyngi_imgcmp's "rel_mse" of IMAGE against REFERENCE, or -1.
double relMse(const TempDir& dir, const std::string& reference, const std::string& image) {
  const SampleRun r = runSample(DYNGI_IMGCMP_EXE, quoted(reference) + " " + quoted(image), dir, 60);
  const size_t at = r.out.find("\"rel_mse\": ");
  return r.exitCode == 0 && at != std::string::npos ? std::stod(r.out.substr(at + 11)) : -1.0;
}
}  // namespace

// A host that is not dyngi (examples/own_renderer: its own device, glTF loading, reversed-Z depth and
// octahedral normals, its own direct lighting), built against the installed package: with the
// validation layer and its synchronization checks on it runs clean, its image is lit with bounce light on
// the ceiling, and the GI's indirect light it gets through the host API equals dyngi_sample's
// `--view indirect` of the same scene, camera, size, technique and frames for every technique.
TEST(Install, OwnRendererGetsTheSamplesIndirectLightThroughTheHostApi) {
  TempDir dir;
  const SampleRun built = installAndRun(dir, dir.file("out"), 1);
  ASSERT_EQ(built.exitCode, 0) << built.err << "\n(logs: own-configure.log, own-build.log in the temporary directory)";
  const std::string own = dir.file("out/own-build/own_renderer"), scene = quoted(DYNGI_SOURCE_DIR "/assets/cornell_box.gltf");
  for (const char* technique : {"temporal", "many-lights", "vct"}) {
    const std::string png = dir.file(std::string(technique) + ".png"), exr = dir.file(std::string(technique) + "_own.exr"),
                      reference = dir.file(std::string(technique) + "_sample.exr");
    const SampleRun r = runSample(own, scene + " " + quoted(png) + " --technique " + technique +
                                           " --frames 30 --size 128x128 --validation --indirect-out " + quoted(exr),
                                  dir, 300);
    ASSERT_EQ(r.exitCode, 0) << technique << ": " << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    const SampleRun s = runSample(DYNGI_SAMPLE_EXE, "--headless --scene " + scene + " --gi " + technique +
                                                        " --view indirect --size 128x128 --frames 30 --hdr-out " + quoted(reference),
                                  dir, 300);
    ASSERT_EQ(s.exitCode, 0) << s.err;
    const double rel = relMse(dir, reference, exr);
    std::printf("own_renderer --technique %s: indirect light against dyngi_sample --view indirect: relMSE %.2e\n", technique, rel);
    EXPECT_GE(rel, 0.0) << technique;
    EXPECT_LE(rel, 0.01) << technique;
    const PngFigures f = measure(png);
    EXPECT_GT(f.mean, 10.0) << technique << ": lit";
    EXPECT_LT(f.clipped, 0.05) << technique << ": not saturated";
    EXPECT_GT(f.ceilingMean, 15.0) << technique << ": the ceiling gets bounce light";
  }
  const std::string png = quoted(dir.file("x.png"));
  const std::string bad[] = {"/nonexistent.gltf " + png, scene + " " + png + " --technique no_such_technique", scene + " " + png + " --frames -3",
                             scene + " " + png + " --size 0x4", ""};
  for (const std::string& args : bad) {
    const SampleRun r = runSample(own, args, dir, 120);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}
