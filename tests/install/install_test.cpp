// The drop-in subsystem end to end: scripts/test_install.sh installs dyngi to a fresh prefix, builds
// examples/minimal_host and examples/own_renderer against that prefix with a clean CMake configure, and
// runs them on assets/cornell_box.gltf. The images they write must be lit, and lit by the GI: the ceiling
// is outside the spot's cone (it points down), so only bounce light reaches it.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include "support/sample_run.h"
#include "support/temp_dir.h"
#include "support/virtual_display.h"

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
// `--view indirect` of the same scene, camera, size, technique and frames for every technique, on the
// Cornell box and on the Cornell box with a skinned bar bending.
TEST(Install, OwnRendererGetsTheSamplesIndirectLightThroughTheHostApi) {
  TempDir dir;
  const SampleRun built = installAndRun(dir, dir.file("out"), 1);
  ASSERT_EQ(built.exitCode, 0) << built.err << "\n(logs: own-configure.log, own-build.log in the temporary directory)";
  const std::string own = dir.file("out/own-build/own_renderer"), scene = quoted(DYNGI_SOURCE_DIR "/assets/cornell_box.gltf");
  // The skinned scene: the Cornell box with a bar that bends over its 30 frames (the host skins it on the
  // CPU and hands the GI each pose through updateMesh).
  const std::string skinned = quoted(dir.file("cornell_skinned_bar.gltf"));
  ASSERT_EQ(runSample(DYNGI_MAKE_SCENE_EXE, skinned + " --skinned-bar", dir, 60).exitCode, 0);
  for (const std::string& file : {scene, skinned})
    for (const char* technique : {"temporal", "many-lights", "vct"}) {
      const std::string name = std::string(file == scene ? "cornell_" : "skinned_") + technique;
      const std::string png = dir.file(name + ".png"), exr = dir.file(name + "_own.exr"), reference = dir.file(name + "_sample.exr");
      const SampleRun r = runSample(own, file + " " + quoted(png) + " --technique " + technique +
                                             " --frames 30 --size 128x128 --validation --indirect-out " + quoted(exr),
                                    dir, 300);
      ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
      EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
      const SampleRun s = runSample(DYNGI_SAMPLE_EXE, "--headless --scene " + file + " --gi " + technique +
                                                          " --view indirect --size 128x128 --frames 30 --hdr-out " + quoted(reference),
                                    dir, 300);
      ASSERT_EQ(s.exitCode, 0) << s.err;
      const double rel = relMse(dir, reference, exr);
      std::printf("own_renderer %s: indirect light against dyngi_sample --view indirect: relMSE %.2e\n", name.c_str(), rel);
      EXPECT_GE(rel, 0.0) << name;
      // The same GI on the same pixels: 0 here. A pose the GI missed (the bar drawn bent, voxelized
      // straight) measured 3.3e-4, inside a loose 0.01, so the bound is 1e-5.
      EXPECT_LE(rel, 1e-5) << name;
      const PngFigures f = measure(png);
      EXPECT_GT(f.mean, 10.0) << name << ": lit";
      EXPECT_LT(f.clipped, 0.05) << name << ": not saturated";
      EXPECT_GT(f.ceilingMean, 15.0) << name << ": the ceiling gets bounce light";
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

// The same host in a window (GLFW swapchain) under Xvfb: a run of 60 presented frames is clean under the
// validation layer's synchronization checks and exits 0 with a lit image, and what reaches the screen is
// the lit Cornell box: a screenshot of the window, taken while it runs, is lit, red on the left.
TEST(Install, OwnRendererPresentsInAWindow) {
  DYNGI_REQUIRE_PROGRAM("Xvfb");
  DYNGI_REQUIRE_PROGRAM("import");
  TempDir dir;
  const SampleRun built = installAndRun(dir, dir.file("out"), 1);
  ASSERT_EQ(built.exitCode, 0) << built.err;
  VirtualDisplay xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "Xvfb did not start";
  const std::string own = "env DISPLAY=" + xvfb.display() + " " + dir.file("out/own-build/own_renderer");
  const std::string scene = quoted(DYNGI_SOURCE_DIR "/assets/cornell_box.gltf"), png = dir.file("window.png");
  const SampleRun r = runSample(own, scene + " " + quoted(png) + " --technique vct --window --frames 60 --size 128x128 --validation", dir, 300);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  EXPECT_GT(measure(png).mean, 10.0) << "lit";

  // The screen: the window sits at the display's corner (no window manager); shot until it shows.
  const std::string pidFile = dir.file("own.pid"), shot = dir.file("shot.png");
  const std::string start = own + " " + scene + " " + quoted(dir.file("long.png")) +
                            " --technique vct --window --frames 100000 --size 128x128 >/dev/null 2>&1 & echo $! > " + quoted(pidFile);
  ASSERT_EQ(std::system(start.c_str()), 0);
  int pid = 0;
  std::ifstream(pidFile) >> pid;
  double mean = 0, red = 0, green = 0;
  for (int i = 0; i < 120 && mean <= 10.0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const std::string grab = "env DISPLAY=" + xvfb.display() + " import -window root -crop 128x128+0+0 " + quoted(shot) + " 2>/dev/null";
    if (std::system(grab.c_str()) != 0) continue;
    int w = 0, h = 0, n = 0;
    unsigned char* p = stbi_load(shot.c_str(), &w, &h, &n, 3);
    if (!p) continue;
    double sum = 0, redSum = 0, greenSum = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const unsigned char* c = p + 3 * (size_t(y) * size_t(w) + size_t(x));
        sum += (c[0] + c[1] + c[2]) / 3.0;
        if (x < w / 8 && y > h / 4 && y < h * 3 / 4) redSum += c[0], greenSum += c[1];
      }
    stbi_image_free(p);
    mean = sum / (double(w) * h), red = redSum, green = greenSum;
  }
  if (pid > 0) kill(pid, SIGTERM);
  std::printf("own_renderer --window: screenshot mean %.1f, left wall red %.0f green %.0f\n", mean, red, green);
  EXPECT_GT(mean, 10.0) << "the window shows the lit scene";
  EXPECT_GT(red, 2.0 * green) << "the red wall on the left, as the PNG has it";
}
