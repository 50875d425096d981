// The sample's run statistics: medians as documented, and nothing timed reads as null, not as zero.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "dyngi/engine/render/image_io.h"
#include "stats.h"
#include "support/temp_dir.h"

using dyngi::sample::percentile;
using dyngi::sample::RunStats;

TEST(RunStats, MedianIsTheMiddleValueOrTheMeanOfTheMiddlePair) {
  EXPECT_DOUBLE_EQ(percentile({5, 1, 3}, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.95), 10.0);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

TEST(RunStats, NoTimedFrameIsNullNotZero) {
  RunStats s;
  s.frames = 2;
  s.warmupFrames = 2;
  nlohmann::json j = nlohmann::json::parse(s.toJson());
  EXPECT_TRUE(j["frame_ms"]["median"].is_null()) << j;
  EXPECT_TRUE(j["frame_ms"]["p95"].is_null()) << j;
  EXPECT_NE(s.table().find("no frame timed"), std::string::npos);
  s.frameMs = {10.0, 30.0, 20.0};
  s.sections["settings"]["clamp"] = 1e-5;  // written exactly, not rounded to a fixed number of decimals
  s.scene = "caf\xe9.glb";                  // not UTF-8: replaced, not thrown
  j = nlohmann::json::parse(s.toJson());
  EXPECT_EQ(j["frame_ms"]["median"], 20.0);
  EXPECT_EQ(j["settings"]["clamp"], 1e-5);
}

TEST(RunStats, SeriesKeepEverySampleUpToCapacityThenABoundedUniformSubset) {
  using dyngi::sample::SampleSeries;
  // Short runs: exact medians, as before.
  SampleSeries shortRun;
  for (int i = 0; i < 1001; ++i) shortRun.push(double(i));
  EXPECT_EQ(shortRun.kept().size(), 1001u);
  EXPECT_DOUBLE_EQ(shortRun.percentile(0.5), 500.0);
  // A long windowed session (a million frames): memory stays at the capacity, and the median of the
  // kept subset estimates the true one (uniform 0..1e6: 5e5) to about 1/sqrt(capacity) in rank.
  SampleSeries longRun;
  const size_t capacityBefore = [&] {
    longRun.push(0.0);
    return longRun.kept().capacity();
  }();
  for (int i = 1; i < 1000000; ++i) longRun.push(double(i));
  EXPECT_EQ(longRun.seen(), 1000000u);
  EXPECT_EQ(longRun.kept().size(), SampleSeries::kCapacity);
  EXPECT_EQ(longRun.kept().capacity(), capacityBefore) << "no allocation after the first sample";
  EXPECT_NEAR(longRun.percentile(0.5), 5e5, 0.05 * 1e6);
  EXPECT_NEAR(longRun.percentile(0.95), 9.5e5, 0.05 * 1e6);
  EXPECT_EQ(longRun.max(), 999999.0) << "the maximum is exact, kept or not";
  // Samples late in the run are represented: a run whose second half is slower shows it in its median.
  SampleSeries stepUp;
  for (int i = 0; i < 200000; ++i) stepUp.push(i < 100000 ? 10.0 : 30.0);
  EXPECT_NEAR(stepUp.percentile(0.25), 10.0, 1e-9);
  EXPECT_NEAR(stepUp.percentile(0.75), 30.0, 1e-9);
}

TEST(ImageIo, WritersFailCleanlyOnPathsTheyCannotWriteAndCreateNoDirectory) {
  // (Under the sanitizer job a leak on these error paths fails the test: tinyexr's own file writer
  // leaked its header here.)
  dyngi::test::TempDir dir;
  const std::vector<glm::vec4> hdr(16 * 16, glm::vec4(0.5f));
  const std::vector<uint8_t> ldr(16 * 16 * 4, 128);
  const std::string missing = dir.file("no/such/dir/x");
  std::string err = dyngi::render::writeExr(missing + ".exr", 16, 16, hdr);
  EXPECT_NE(err.find("does not exist"), std::string::npos) << err;
  EXPECT_NE(dyngi::render::writePng(missing + ".png", 16, 16, ldr), "");
  EXPECT_FALSE(std::filesystem::exists(dir.file("no"))) << "no directory made on the side";
  // A full disk is an error, not "wrote"; a FIFO is refused at once, not waited on.
  if (std::filesystem::exists("/dev/full")) {
    EXPECT_NE(dyngi::render::writeExr("/dev/full", 16, 16, hdr).find("could not be written"), std::string::npos);
    EXPECT_NE(dyngi::render::writePng("/dev/full", 16, 16, ldr).find("could not be written"), std::string::npos);
  }
  ASSERT_EQ(::mkfifo(dir.file("fifo.png").c_str(), 0600), 0);
  EXPECT_NE(dyngi::render::writePng(dir.file("fifo.png"), 16, 16, ldr).find("is a FIFO"), std::string::npos);
  // And where the directory exists, both write, and the EXR reads back what was written.
  ASSERT_EQ(dyngi::render::writeExr(dir.file("x.exr"), 16, 16, hdr), "");
  uint32_t w = 0, h = 0;
  std::vector<glm::vec4> back;
  ASSERT_EQ(dyngi::render::readExr(dir.file("x.exr"), w, h, back), "");
  EXPECT_EQ(w, 16u);
  EXPECT_FLOAT_EQ(back[17].g, 0.5f);
}
