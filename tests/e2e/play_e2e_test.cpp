// The playable sample end to end: a scripted session (--input-script) in a real window under Xvfb
// selects the short box with a click at its projected centre, drags it, switches the GI on, to voxel cone
// tracing, by clicking the panel's radio button, and takes a screenshot. The same script replayed
// headless (--ui on) must give the same 3D view; the X server's own capture of the window must show
// what the sample says it presented; the panel must be there; no validation errors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <glm/glm.hpp>

#include "dyngi/engine/render/image_io.h"
#include "dyngi/engine/render/image_metrics.h"
#include "support/sample_run.h"
#include "support/shared_scenes.h"
#include "support/temp_dir.h"
#include "support/virtual_display.h"

using dyngi::test::SampleRun;
using dyngi::test::TempDir;
using dyngi::test::VirtualDisplay;

namespace {

constexpr int kSize = 768;
constexpr int kPanelRight = 310;  // the panel is 300 px wide at x = 8; the 3D view is compared right of it

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  bool ok() const { return width > 0; }
  const unsigned char* at(int x, int y) const { return &rgb[3 * (size_t(y) * size_t(width) + size_t(x))]; }
};

Png readPng(const std::string& path) {
  Png p;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.width, &p.height, &n, 3);
  if (!data) return Png{};
  p.rgb.assign(data, data + size_t(p.width) * size_t(p.height) * 3);
  stbi_image_free(data);
  return p;
}

// Mean and 99th percentile of |a - b| (0..255, per channel) over x in [x0, x1) of both images' top-left
// kSize x kSize.
std::pair<double, double> difference(const Png& a, const Png& b, int x0, int x1) {
  std::vector<int> d;
  double sum = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const int v = std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
        d.push_back(v);
        sum += v;
      }
  std::sort(d.begin(), d.end());
  return {sum / double(d.size()), double(d[d.size() * 99 / 100])};
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f, nullptr, false);
}

// The session: the short box's projected centre at 768^2 (the built-in Cornell camera) is (486, 590).
std::string script(const std::string& screenshot, int quitAt) {
  return "# select the short box, drag it, switch to VCT in the panel, take a screenshot\n"
         "5 click 486 590\n"
         "8 drag 486 590 600 560 10\n"
         "25 ui vct\n"
         "32 screenshot " + screenshot + "\n" +
         (quitAt > 0 ? std::to_string(quitAt) + " quit\n" : std::string());
}

}  // namespace

TEST(SamplePlay, ScriptedWindowSessionSelectsDragsSwitchesAndMatchesItsHeadlessReplay) {
  DYNGI_REQUIRE_PROGRAM("Xvfb");
  DYNGI_REQUIRE_PROGRAM("import");  // ImageMagick
  VirtualDisplay xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "Xvfb did not start";
  TempDir dir;
  const std::string windowShot = dir.file("window.png"), headlessShot = dir.file("headless.png"), screen = dir.file("screen.png");
  std::ofstream(dir.file("window.txt")) << script(windowShot, 60);
  std::ofstream(dir.file("headless.txt")) << script(headlessShot, 0);
  // GI off at the start: the panel's click makes the GI system (GiControl), the costly part of the
  // session begins there.
  const std::string common = " --scene cornell --gi off --size 768x768 --validation";

  // The window: started in the background; once its screenshot exists (frame 32), the X server's view of
  // the screen is captured while the session keeps running (it quits at frame 60).
  const std::string run = "DISPLAY=" + xvfb.display() + " timeout -s KILL 400 " DYNGI_SAMPLE_EXE + common + " --input-script " +
                          dir.file("window.txt") + " --stats " + dir.file("window.json") + " >" + dir.file("window.log") + " 2>&1; echo $? > " +
                          dir.file("window.rc");
  std::ofstream(dir.file("session.sh")) << "(" << run << ") &\n"
                                        << "for i in $(seq 1 3000); do [ -f " << windowShot << " ] && break; sleep 0.1; done\n"
                                        << "sleep 0.3\nDISPLAY=" << xvfb.display() << " import -window root " << screen << "\nwait\n";
  ASSERT_EQ(std::system(("bash " + dir.file("session.sh")).c_str()), 0);
  std::string rc;
  std::ifstream(dir.file("window.rc")) >> rc;
  std::stringstream log;
  log << std::ifstream(dir.file("window.log")).rdbuf();
  ASSERT_EQ(rc, "0") << log.str();

  const SampleRun headless =
      dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --ui on" + common + " --input-script " + dir.file("headless.txt") + " --stats " +
                                                   dir.file("headless.json"),
                             dir, 400);
  ASSERT_EQ(headless.exitCode, 0) << headless.err;

  // What the session did, from each run's stats.
  for (const char* which : {"window.json", "headless.json"}) {
    SCOPED_TRACE(which);
    const nlohmann::json s = readJson(dir.file(which));
    ASSERT_TRUE(s.contains("play")) << s.dump();
    EXPECT_EQ(s["play"]["gi_mode"], "vct") << "the panel's radio button switched the GI";
    EXPECT_EQ(s["play"]["selected"], "short_box") << "the click at its projected centre selected it";
    EXPECT_EQ(s["play"]["last_action"], "moved short_box") << "the drag moved it";
    EXPECT_EQ(s["counts"]["validation_errors"], 0);
    EXPECT_TRUE(s["stages_ms"].contains("inject") && s["stages_ms"].contains("trace")) << "voxel cone tracing ran";
    EXPECT_TRUE(s["stages_ms"].contains("ui")) << "the panel was drawn";
  }

  const Png window = readPng(windowShot), replay = readPng(headlessShot), captured = readPng(screen);
  ASSERT_TRUE(window.ok() && replay.ok() && captured.ok());
  ASSERT_EQ(window.width, kSize);
  ASSERT_GE(captured.width, kSize);
  ASSERT_GE(captured.height, kSize);
  // The 3D view in the window is the headless replay's: same input, same fixed time step.
  const auto [meanReplay, p99Replay] = difference(window, replay, kPanelRight, kSize);
  std::printf("window vs headless replay (3D view): mean %.3f, p99 %.1f of 255\n", meanReplay, p99Replay);
  EXPECT_LT(meanReplay, 0.5);
  EXPECT_LE(p99Replay, 2.0);
  // The X server shows the window at the screen's top left with what the sample presented (a few frames
  // later: the voxel blend is still settling, and the panel's frame time changes).
  const auto [meanScreen, p99Screen] = difference(window, captured, kPanelRight, kSize);
  std::printf("window screenshot vs X capture (3D view): mean %.3f, p99 %.1f of 255\n", meanScreen, p99Screen);
  EXPECT_LT(meanScreen, 3.0);
  // The panel is there: its title bar is ImGui's blue, its body dark grey, and the 3D view is not.
  auto meanRgb = [](const Png& p, int x0, int y0, int x1, int y1) {
    glm::dvec3 m(0.0);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) m += glm::dvec3(p.at(x, y)[0], p.at(x, y)[1], p.at(x, y)[2]);
    return m / double((x1 - x0) * (y1 - y0));
  };
  for (const Png* p : {&window, &captured}) {
    const glm::dvec3 title = meanRgb(*p, 60, 10, 290, 24);
    EXPECT_GT(title.b, title.r + 25) << "the panel's title bar (" << title.r << ", " << title.g << ", " << title.b << ")";
    // Equal images prove nothing if both are black or white: the 3D view is lit, not washed out.
    const glm::dvec3 view = meanRgb(*p, kPanelRight, 0, kSize, kSize);
    EXPECT_GT(view.r + view.g + view.b, 3 * 15.0) << "the 3D view is lit";
    EXPECT_LT(view.r + view.g + view.b, 3 * 200.0) << "the 3D view is not washed out";
  }
}

// A script that cannot be replayed is bad input: one line, exit 2, before any window or device.
TEST(SamplePlay, BadInputScriptsExitWithCode2AndOneLine) {
  TempDir dir;
  const char* bad[] = {"5 klick 10 10\n", "x move 1 2\n", "3 move 1\n", "4 drag 0 0 10 10 0\n", "5 key NOSUCHKEY\n", "6 press thumb\n",
                       "7 ui\n", "8 move 1 2 3\n", "-1 quit\n", "99999999999 quit\n", "9 move 1e300 5\n", "3 resize 0 5\n"};
  int i = 0;
  for (const char* text : bad) {
    const std::string path = dir.file("bad" + std::to_string(i++) + ".txt");
    std::ofstream(path) << text;
    const SampleRun r = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --frames 2 --input-script " + path, dir, 60);
    EXPECT_EQ(r.exitCode, 2) << text << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << text << r.err;
    EXPECT_NE(r.err.find(":1:"), std::string::npos) << "names the line: " << r.err;
  }
  const SampleRun missing = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --input-script /nonexistent/script.txt", dir, 60);
  EXPECT_EQ(missing.exitCode, 2) << missing.err;
  const SampleRun record = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --record /nonexistent/dir", dir, 60);
  EXPECT_EQ(record.exitCode, 2) << record.err;
  const SampleRun ui = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --ui maybe", dir, 60);
  EXPECT_EQ(ui.exitCode, 2) << ui.err;
}

// --record writes every frame's displayed image, numbered.
TEST(SamplePlay, RecordWritesNumberedFrames) {
  TempDir dir;
  std::filesystem::create_directory(dir.file("frames"));
  const SampleRun r = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless --size 64x64 --frames 3 --record " + dir.file("frames"), dir, 120);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f : {"frame_00000.png", "frame_00001.png", "frame_00002.png"}) {
    const Png p = readPng(dir.file(std::string("frames/") + f));
    EXPECT_EQ(p.width, 64) << f;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("frames/frame_00003.png")));
}

// --gi path in a window: the progressive preview's mean after N frames is the path tracer's image at N
// samples per pixel, within the path tracer's own seed-to-seed noise at that count.
TEST(SamplePlay, PathTracedPreviewInAWindowConvergesToThePathTracer) {
  DYNGI_REQUIRE_PROGRAM("Xvfb");
  VirtualDisplay xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "Xvfb did not start";
  TempDir dir;
  constexpr int kFrames = 32;
  std::ofstream(dir.file("quit.txt")) << kFrames - 1 << " quit\n";
  const std::string common = " --gi path --scene cornell --size 96x96 --ui off";
  const SampleRun window = dyngi::test::runSample(
      "env DISPLAY=" + xvfb.display() + " " DYNGI_SAMPLE_EXE,
      common + " --validation --input-script " + dir.file("quit.txt") + " --hdr-out " + dir.file("preview.exr") + " --stats " + dir.file("preview.json"),
      dir, 300);
  ASSERT_EQ(window.exitCode, 0) << window.err;
  const nlohmann::json s = readJson(dir.file("preview.json"));
  EXPECT_EQ(s["counts"]["path_preview_spp"], kFrames) << "a sample per pixel a frame, never restarted in a still scene";
  EXPECT_EQ(s["counts"]["validation_errors"], 0);
  auto reference = [&](int seed) {
    const std::string out = dir.file("path" + std::to_string(seed) + ".exr");
    const SampleRun r = dyngi::test::runSample(DYNGI_SAMPLE_EXE, "--headless" + common + " --spp " + std::to_string(kFrames) + " --seed " +
                                                                     std::to_string(seed) + " --hdr-out " + out,
                                               dir, 300);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    dyngi::render::ImageRgba img;
    uint32_t w = 0, h = 0;
    EXPECT_EQ(dyngi::render::readExr(out, w, h, img), "");
    return img;
  };
  dyngi::render::ImageRgba preview;
  uint32_t w = 0, h = 0;
  ASSERT_EQ(dyngi::render::readExr(dir.file("preview.exr"), w, h, preview), "");
  const dyngi::render::ImageRgba a = reference(11), b = reference(12);
  ASSERT_EQ(preview.size(), a.size());
  const double noise = dyngi::render::relativeMse(b, a), error = dyngi::render::relativeMse(preview, a);
  const glm::dvec3 mp = dyngi::render::meanOver(preview), ma = dyngi::render::meanOver(a);
  std::printf("preview vs path tracer: relMSE %.4f (seed to seed %.4f), mean ratio %.4f\n", error, noise, (mp.r + mp.g + mp.b) / (ma.r + ma.g + ma.b));
  EXPECT_LT(error, 1.5 * noise) << "the preview is the path tracer's image, up to its noise";
  EXPECT_NEAR((mp.r + mp.g + mp.b) / (ma.r + ma.g + ma.b), 1.0, 0.03);
}

// A resize mid-session (the window system's, as a user's drag would do it): the swapchain, the targets and
// the panel's framebuffer follow, and the frame after it is whole: lit, panel drawn, no validation error.
TEST(SamplePlay, ResizeMidSessionKeepsTheSceneAndThePanel) {
  DYNGI_REQUIRE_PROGRAM("Xvfb");
  VirtualDisplay xvfb;
  ASSERT_FALSE(xvfb.display().empty()) << "Xvfb did not start";
  TempDir dir;
  for (const bool window : {true, false}) {
    SCOPED_TRACE(window ? "window" : "headless");
    const std::string shot = dir.file(window ? "window.png" : "headless.png");
    std::ofstream(dir.file("resize.txt")) << "3 resize 640 400\n8 screenshot " << shot << "\n9 quit\n";
    const SampleRun r = dyngi::test::runSample(
        (window ? "env DISPLAY=" + xvfb.display() + " " : std::string()) + DYNGI_SAMPLE_EXE,
        std::string(window ? "" : "--headless --ui on") + " --scene cornell --gi temporal --size 320x320 --validation --input-script " + dir.file("resize.txt"),
        dir, 300);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Png p = readPng(shot);
    ASSERT_EQ(p.width, 640);
    ASSERT_EQ(p.height, 400);
    double scene = 0;
    for (int y = 0; y < 400; ++y)
      for (int x = 320; x < 640; ++x) scene += p.at(x, y)[0] + p.at(x, y)[1] + p.at(x, y)[2];
    EXPECT_GT(scene / (3.0 * 320 * 400), 10.0) << "the scene is drawn at the new size";
    double r0 = 0, b0 = 0;
    for (int y = 10; y < 24; ++y)
      for (int x = 60; x < 290; ++x) r0 += p.at(x, y)[0], b0 += p.at(x, y)[2];
    EXPECT_GT(b0, r0 * 1.3) << "the panel's title bar";
  }
}
