// The sample end to end, as a user runs it: every --gi mode, every --animate scene and every --view
// runs to exit 0 and writes a PNG, an EXR and a stats JSON; the images are not black and the JSON has
// the documented keys. Hostile scene files end in one line and exit 2 (or render), never in a hang.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "dyngi/engine/render/image_io.h"
#include "support/gltf_writer.h"
#include "dyngi/gi/technique.h"
#include "support/sample_run.h"
#include "support/shared_scenes.h"
#include "support/temp_dir.h"

using dyngi::test::SampleRun;
using dyngi::test::TempDir;

namespace {

SampleRun runSample(const std::string& args, const TempDir& dir, int timeoutSeconds = 180) {
  return dyngi::test::runSample(DYNGI_SAMPLE_EXE, args, dir, timeoutSeconds);
}

// The outputs of one run, read back and checked for what every good frame has.
struct Outputs {
  double pngMean = 0;      // mean of the sRGB channels, 0..255
  double pngSpread = 0;    // standard deviation of the pixels' mean channel: 0 for a flat image
  double pngClipped = 0;   // fraction of pixels with every channel at 250 or more (washed out)
  double exrMean = 0;      // mean linear radiance (rgb)
  bool exrFinite = true;
  nlohmann::json stats;
};

// A frame a user would accept: not black, not washed out, not flat. (Measured on the Cornell scenes at
// 64^2: mean 13-45, spread 37-70, clipped 0%; the debug views: mean 20-145, spread 13-80, up to 10%
// clipped where the vpls view marks its VPLs white.)
// Views of a fraction (VCT's ao and opacity: 1 is white) may be bright: maxMean.
void expectAGoodImage(const Outputs& o, const std::string& what, double minMean = 10.0, double maxMean = 200.0) {
  EXPECT_TRUE(o.exrFinite) << what;
  EXPECT_GT(o.pngMean, minMean) << what << ": black";
  EXPECT_LT(o.pngMean, maxMean) << what << ": washed out";
  EXPECT_LT(o.pngClipped, 0.25) << what << ": a quarter of the pixels clipped to white";
  EXPECT_GT(o.pngSpread, minMean) << what << ": flat";
  std::printf("%-28s mean %.1f spread %.1f clipped %.1f%%\n", what.c_str(), o.pngMean, o.pngSpread, 100 * o.pngClipped);
}

Outputs readOutputs(const TempDir& dir, uint32_t width, uint32_t height) {
  Outputs o;
  int w = 0, h = 0, n = 0;
  unsigned char* png = stbi_load(dir.file("frame.png").c_str(), &w, &h, &n, 3);
  EXPECT_NE(png, nullptr) << "PNG written and decodable";
  if (png) {
    EXPECT_EQ(uint32_t(w), width);
    EXPECT_EQ(uint32_t(h), height);
    double sum = 0, sum2 = 0, clipped = 0;
    for (int i = 0; i < w * h; ++i) {
      const double v = (png[3 * i] + png[3 * i + 1] + png[3 * i + 2]) / 3.0;
      sum += v;
      sum2 += v * v;
      clipped += png[3 * i] >= 250 && png[3 * i + 1] >= 250 && png[3 * i + 2] >= 250;
    }
    const double pixels = double(w) * h;
    o.pngMean = sum / pixels;
    o.pngSpread = std::sqrt(std::max(0.0, sum2 / pixels - o.pngMean * o.pngMean));
    o.pngClipped = clipped / pixels;
    stbi_image_free(png);
  }
  uint32_t ew = 0, eh = 0;
  std::vector<glm::vec4> hdr;
  EXPECT_EQ(dyngi::render::readExr(dir.file("frame.exr"), ew, eh, hdr), "");
  EXPECT_EQ(ew, width);
  double sum = 0;
  for (const auto& p : hdr) {
    o.exrFinite &= std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b);
    sum += double(p.r + p.g + p.b) / 3.0;
  }
  o.exrMean = hdr.empty() ? 0 : sum / double(hdr.size());
  std::ifstream f(dir.file("stats.json"));
  std::stringstream ss;
  ss << f.rdbuf();
  o.stats = nlohmann::json::parse(ss.str(), nullptr, /*allow_exceptions=*/false);
  EXPECT_FALSE(o.stats.is_discarded()) << "stats.json parses: " << ss.str();
  return o;
}

// The keys the README documents for --stats.
void expectDocumentedKeys(const nlohmann::json& j, const std::string& gi, bool vplPaths) {
  for (const char* key : {"scene", "size", "gi", "device", "frames", "warmup_frames", "frame_ms", "stages_ms", "cpu_ms", "counts"})
    EXPECT_TRUE(j.contains(key)) << "stats.json lacks '" << key << "': " << j.dump();
  if (j.is_discarded()) return;
  EXPECT_EQ(j.value("gi", ""), gi);
  ASSERT_TRUE(j["frame_ms"].is_object());
  EXPECT_TRUE(j["frame_ms"].contains("median") && j["frame_ms"].contains("p95"));
  EXPECT_TRUE(j["frame_ms"]["median"].is_number()) << "a timed frame";
  if (vplPaths) {
    ASSERT_TRUE(j.contains("vpl")) << j.dump();
    for (const char* key : {"count", "valid", "invalidated_total", "replaced_total", "reshoot_budget"})
      EXPECT_TRUE(j["vpl"].contains(key)) << "vpl." << key;
    EXPECT_GT(j["vpl"].value("valid", 0.0), 0.0);
  }
}

const char* kOutputs = " --out OUT/frame.png --hdr-out OUT/frame.exr --stats OUT/stats.json";

std::string withOutputs(const TempDir& dir) {
  std::string s = kOutputs;
  for (size_t at; (at = s.find("OUT/")) != std::string::npos;) s.replace(at, 4, dir.file(""));
  return s;
}

struct GiCase {
  const char* name;
  const char* args;
  bool vplPaths;
};

class SampleGiMode : public ::testing::TestWithParam<GiCase> {};

}  // namespace

TEST_P(SampleGiMode, WritesAGoodFrame) {
  const GiCase& c = GetParam();
  TempDir dir;
  SampleRun r = runSample(std::string("--headless --validation --size 64x64 --frames 4 ") + c.args + withOutputs(dir), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
  Outputs o = readOutputs(dir, 64, 64);
  expectAGoodImage(o, std::string("--gi ") + c.name);
  EXPECT_GT(o.exrMean, 0.01);
  expectDocumentedKeys(o.stats, o.stats.value("gi", ""), c.vplPaths);
  EXPECT_EQ(o.stats["size"], nlohmann::json::array({64, 64}));
}

INSTANTIATE_TEST_SUITE_P(Sample, SampleGiMode,
                         ::testing::Values(GiCase{"off", "--gi off", false}, GiCase{"temporal", "--gi temporal", true},
                                           GiCase{"temporal_bvh", "--gi temporal --visibility bvh", true},
                                           GiCase{"many_lights", "--gi many-lights --vpls 64", false},
                                           GiCase{"vct", "--gi vct", false}, GiCase{"path", "--gi path --spp 4", false}),
                         [](const auto& p) { return std::string(p.param.name); });

// dyngi_imgcmp's region means: an image against itself reads a ratio of 1 in every region; the frame
// with GI against the one without reads more than 1 over the whole image, the same as the tool's own
// whole-image mean_ratio; a region outside the image or malformed is one error line and exit 2.
TEST(ImageCompare, RegionMeansAndBadRegions) {
  TempDir dir;
  for (const char* gi : {"off", "vct"}) {
    SampleRun r = runSample(std::string("--headless --frames 2 --size 32x32 --voxel-resolution 64 --gi ") + gi + " --hdr-out " +
                                dir.file(std::string(gi) + ".exr"),
                            dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  const std::string off = dir.file("off.exr"), vct = dir.file("vct.exr");
  auto compare = [&](const std::string& image, const std::string& args) {
    return dyngi::test::runSample(DYNGI_IMGCMP_EXE, off + " " + image + " " + args, dir, 60);
  };
  SampleRun same = compare(off, "--region 0,0,16,16 --region 8,4,24,28");
  ASSERT_EQ(same.exitCode, 0) << same.err;
  const nlohmann::json j = nlohmann::json::parse(same.out);
  ASSERT_EQ(j["regions"].size(), 2u) << j.dump();
  for (const auto& region : j["regions"]) {
    EXPECT_GT(region["reference"].get<double>(), 0.0) << "the Cornell box is lit there";
    EXPECT_DOUBLE_EQ(region["ratio"].get<double>(), 1.0);
  }
  EXPECT_EQ(j["regions"][1]["rect"], nlohmann::json::array({8, 4, 24, 28}));
  EXPECT_TRUE(j["psnr"].is_null()) << "equal images: no finite PSNR, and still valid JSON";
  SampleRun withGi = compare(vct, "--region 0,0,32,32");
  ASSERT_EQ(withGi.exitCode, 0) << withGi.err;
  const nlohmann::json g = nlohmann::json::parse(withGi.out);
  EXPECT_GT(g["mean_ratio"].get<double>(), 1.01) << "bounce light adds to the direct";
  EXPECT_NEAR(g["regions"][0]["ratio"].get<double>(), g["mean_ratio"].get<double>(), 1e-3);
  for (const char* bad : {"--region 30,30,8,8", "--region 1,2", "--region -1,0,4,4", "--region", "--frobnicate x"}) {
    SampleRun b = compare(off, bad);
    EXPECT_EQ(b.exitCode, 2) << bad;
    EXPECT_NE(b.err.find("dyngi_imgcmp"), std::string::npos) << bad << ": " << b.err;
  }
}

// --gi vct with its options: every stage it declares is timed, and its own figures are in the stats.
TEST(SampleVct, TimesEveryStageAndReportsItsSettings) {
  TempDir dir;
  SampleRun r = runSample("--headless --validation --size 64x64 --frames 4 --gi vct --bounces 2 --voxel-resolution 64 --diffuse-cones 4 --trace-scale 1" +
                              withOutputs(dir),
                          dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  Outputs o = readOutputs(dir, 64, 64);
  expectAGoodImage(o, "--gi vct --bounces 2");
  for (const char* stage : {"voxelize", "svo_build", "inject", "mips", "bounce", "trace", "upsample"})
    EXPECT_TRUE(o.stats["stages_ms"].contains(stage)) << stage << " in " << o.stats["stages_ms"].dump();
  ASSERT_TRUE(o.stats.contains("vct")) << o.stats.dump();
  EXPECT_EQ(o.stats["vct"].value("trace_width", 0.0), 64.0);
  EXPECT_EQ(o.stats["settings"].value("bounces", 0.0), 2.0) << o.stats["settings"].dump();
  EXPECT_EQ(o.stats["settings"].value("diffuse-cones", 0.0), 4.0);
  // Its volumes at 64^3 with 2 bounces, by hand: the radiance chain (299593 RGBA16F texels), the atlas
  // (192 x 32 x 32 and 5 levels below, 224694), the direct image and the bounce's (64^3 each):
  // 8388600 bytes, 8 MiB.
  EXPECT_NEAR(o.stats["vct"].value("volume_mib", 0.0), 8388600.0 / 1048576.0, 1e-3);
  // The main job's two moving boxes: the voxels they left are looked for in their boxes, not the whole
  // volume.
  const double cleared = o.stats["vct"].value("cleared_voxels", -1.0);
  EXPECT_GT(cleared, 0.0);
  EXPECT_LT(cleared, 0.5 * 64 * 64 * 64);
  // A value out of its range is one clear error line and exit 2.
  TempDir bad;
  SampleRun b = runSample("--headless --frames 1 --size 32x32 --gi vct --diffuse-cones 0" + withOutputs(bad), bad);
  EXPECT_EQ(b.exitCode, 2);
  EXPECT_NE(b.err.find("--diffuse-cones"), std::string::npos) << b.err;
}

// --stage-times fenced times each pass by the CPU clock between fences at its ends. Its truth is the
// frame's own wall time: the passes, run one after another, add up to most of it and never to more, and
// four times the cone trace's work shows up in the trace's figure as much as in the frame's. (On lavapipe
// the timestamps of the default mode miss compute work: the trace read under a millisecond.)
TEST(SampleStats, FencedStageTimesAccountForTheFrame) {
  struct Run {
    double frame = 0, sum = 0, trace = 0;
  };
  auto run = [](const char* traceFrames) {
    TempDir dir;
    SampleRun r = runSample(std::string("--headless --size 128x128 --frames 10 --warmup 4 --gi vct --voxel-resolution 64 --stage-times fenced "
                                        "--trace-frames ") + traceFrames + " --stats " + dir.file("stats.json"), dir);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(dir.file("stats.json")), nullptr, false);
    Run out;
    if (j.is_discarded()) return out;
    EXPECT_EQ(j.value("stage_times", std::string()), "fenced");
    out.frame = j["frame_ms"].value("median", 0.0);
    for (auto& [name, ms] : j["stages_ms"].items()) out.sum += ms.get<double>();
    out.trace = j["stages_ms"].value("trace", 0.0);
    return out;
  };
  const Run spread = run("4"), every = run("1");
  for (const Run& r : {spread, every})
    EXPECT_LE(r.sum, 1.1 * r.frame) << "passes timed one after another cannot add up to more than the frame";
#ifdef __SANITIZE_ADDRESS__
  // Under the sanitizers the instrumented host code and each fence's submission take most of a frame
  // (1.5 s at 128^2 in the CI's sanitizer job), and the trace's share sinks into their noise: the run
  // above still exercises the fenced timer's code; its figures are checked in the Release job.
  std::printf("sanitizer build: frame %.1f ms, trace %.1f / %.1f ms (not compared)\n", spread.frame, spread.trace, every.trace);
  return;
#endif
  for (const Run& r : {spread, every}) EXPECT_GE(r.sum, 0.5 * r.frame) << "the passes are most of the frame";
  const double moreFrame = every.frame - spread.frame, moreTrace = every.trace - spread.trace;
  ASSERT_GT(moreFrame, 0.2 * spread.frame) << "tracing every pixel each frame costs visibly more";
  EXPECT_GT(moreTrace, 0.5 * moreFrame) << "and the trace's figure shows it";
  EXPECT_LT(moreTrace, 1.5 * moreFrame);
}

TEST(SampleAnimate, EveryScriptedSceneRendersAGoodFrame) {
  for (const char* scene : {"static", "moving-spot", "rotating-object", "moving-camera", "walking-fox", "fox-and-spot", "fox-spot-light-on"}) {
    if (std::string(scene).find("fox") != std::string::npos) {
      DYNGI_SHARED_SCENE_OR_SKIP(fox, "Fox.glb");
    }
    TempDir dir;
    SampleRun r = runSample(std::string("--headless --validation --size 64x64 --frames 4 --gi temporal --animate ") + scene + withOutputs(dir), dir);
    ASSERT_EQ(r.exitCode, 0) << scene << ": " << r.err;
    Outputs o = readOutputs(dir, 64, 64);
    expectAGoodImage(o, std::string("--animate ") + scene);
    expectDocumentedKeys(o.stats, "temporal", true);
    EXPECT_EQ(o.stats.value("scene", ""), std::string("animate:") + scene);
  }
}

// --gi-budget-ms: the stats carry the GI's measured cost and the budget's state and trace. A budget no
// level can meet ends at the floor, says so once on stderr, and still renders a good image.
TEST(SampleBudget, AnUnreachableBudgetEndsAtTheFloorAndSaysSo) {
  TempDir dir;
  SampleRun r = runSample("--headless --validation --size 64x64 --frames 40 --gi temporal --gi-budget-ms 0.001" + withOutputs(dir), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("the GI budget of 0.001 ms was not met"), std::string::npos) << r.err;
  Outputs o = readOutputs(dir, 64, 64);
  expectAGoodImage(o, "--gi-budget-ms 0.001");
  ASSERT_TRUE(o.stats.contains("budget")) << o.stats.dump();
  const auto& b = o.stats["budget"];
  EXPECT_NEAR(b["budget_ms"].get<double>(), 0.001, 1e-9);
  EXPECT_FALSE(b["met"].get<bool>());
  EXPECT_EQ(b["level"], b["floor_level"]);
  EXPECT_GT(b["floor_level"].get<int>(), 0);
  ASSERT_FALSE(b["trace"].empty());
  EXPECT_EQ(b["trace"].back()["knobs"]["vpls_per_frame"], b["knobs"]["vpls_per_frame"]);
  EXPECT_GT(o.stats["gi_ms"]["median"].get<double>(), 0.0);
  EXPECT_NEAR(o.stats["settings"]["gi-budget-ms"].get<double>(), 0.001, 1e-9);
}

// Every view of every technique, as the registry lists them (final and indirect for each, then its
// own), and the voxel scene's without GI.
TEST(SampleView, EveryDebugViewWritesAnImage) {
  std::vector<std::pair<std::string, std::string>> cases = {{"voxels", "off"}, {"svo-steps", "temporal"}};
  for (const dyngi::gi::TechniqueEntry& e : dyngi::gi::techniqueRegistry()) {
    cases.push_back({"final", e.name});
    cases.push_back({"indirect", e.name});
    for (const char* view : e.debugViews) cases.push_back({view, e.name});
  }
  for (const auto& [view, gi] : cases) {
    TempDir dir;
    const std::string fewerVpls = gi == "many-lights" ? " --vpls 64" : "";
    SampleRun r = runSample("--headless --validation --size 64x64 --frames 3 --view " + view + " --gi " + gi + fewerVpls + withOutputs(dir), dir);
    ASSERT_EQ(r.exitCode, 0) << view << " of " << gi << ": " << r.err;
    Outputs o = readOutputs(dir, 64, 64);
    const bool fraction = view == "ao" || view == "opacity";
    expectAGoodImage(o, "--view " + view + " --gi " + gi, 2.0, fraction ? 245.0 : 200.0);
  }
}

TEST(SampleHostileInput, SceneFilesEndInOneLineOrRenderNeverHangOrAbort) {
  // Each file once crashed, hung or aborted a GI run; each now gets its answer in seconds.
  using dyngi::test::GltfSpec;
  struct Case {
    const char* name;
    GltfSpec spec;
    int exitCode;
    const char* mentions;
  };
  auto quad = [] {
    GltfSpec s;
    s.meshes = {{dyngi::test::quadPrimitive(1.0f)}};
    s.lightsJson = {R"({"type":"point","intensity":20})"};
    s.nodes = {{.name = "floor", .mesh = 0}, {.name = "bulb", .light = 0, .transformJson = R"("translation":[0,1,0])"}};
    return s;
  };
  std::vector<Case> cases;
  cases.push_back({"inf_translation", quad(), 2, "translation that is not finite"});
  cases.back().spec.nodes[0].transformJson = R"("translation":[0,1e39,0])";
  cases.push_back({"zero_scale", quad(), 0, ""});
  cases.back().spec.nodes[0].transformJson = R"("scale":[0,0,0])";
  cases.push_back({"wrapping_offset", quad(), 2, "bufferView lies outside its buffer"});
  cases.back().spec.meshes[0][0].positionViewOffsetRaw = "18446744073709551600";
  cases.push_back({"huge_count", quad(), 2, "reads past the end"});
  cases.back().spec.meshes[0][0].positionCountRaw = "4611686018427387904";
  cases.push_back({"huge_coordinates", quad(), 2, "beyond the coordinate range"});
  for (auto& p : cases.back().spec.meshes[0][0].positions) p *= 3e38f;
  for (const Case& c : cases) {
    for (const char* gi : {"off", "temporal", "temporal --visibility bvh", "vct"}) {
      TempDir dir;
      std::string file = dir.write(std::string(c.name) + ".glb", dyngi::test::writeGlb(c.spec));
      SampleRun r = runSample(std::string("--headless --validation --frames 2 --size 32x32 --gi ") + gi + " --scene " + file +
                                  " --out " + dir.file("x.png"),
                              dir, 60);
      EXPECT_EQ(r.exitCode, c.exitCode) << c.name << " --gi " << gi << ": " << r.err;
      if (c.exitCode == 2) {
        EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.name << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name << ": " << r.err;
      } else {
        EXPECT_EQ(r.err.find("validation error"), std::string::npos) << c.name << ": " << r.err;
      }
    }
  }
}

TEST(SampleHostileInput, RenderSizeBeyondDeviceMemoryIsRefusedWithoutLeaks) {
  // 8192^2 with GI needs more than a software device's heap: refused with the limit named, exit 2, and
  // the validation layer (on) sees every object released on the way out.
  TempDir dir;
  SampleRun r = runSample("--headless --validation --frames 1 --size 8192x8192 --gi temporal", dir, 300);
  if (r.exitCode == 0) GTEST_SKIP() << "this device holds an 8192^2 GI frame";
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("device memory"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("MiB heap"), std::string::npos) << "names the limit: " << r.err;
  EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
}

TEST(SampleOptions, AdjustedVplCountIsReportedAsUsed) {
  // 100 VPLs over 3 bounces cannot split evenly: the technique uses 99, the stats say 99 (and what was
  // asked), and one line says why. Both VPL techniques round the same way.
  for (const char* technique : {"--gi temporal", "--gi many-lights"}) {
    TempDir dir;
    SampleRun r = runSample(std::string("--headless --size 32x32 --frames 2 --vpls 100 --bounces 3 ") + technique + " --stats " +
                                dir.file("stats.json"),
                            dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("--vpls 100 is used as 99"), std::string::npos) << r.err;
    std::ifstream f(dir.file("stats.json"));
    nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
    ASSERT_FALSE(j.is_discarded());
    EXPECT_EQ(j["counts"].value("vpls", 0.0), 99.0) << technique;
    EXPECT_EQ(j["counts"].value("vpls_requested", 0.0), 100.0) << technique;
    // Every setting the technique used, from its option table.
    ASSERT_TRUE(j.contains("settings")) << j.dump();
    EXPECT_EQ(j["settings"].value("vpls", 0.0), 99.0);
    EXPECT_EQ(j["settings"].value("bounces", 0.0), 3.0);
    EXPECT_TRUE(j["settings"].contains("interleave") && j["settings"].contains("distance-clamp") && j["settings"].contains("voxel-resolution")) << j.dump();
  }
}
