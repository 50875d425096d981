#include <gtest/gtest.h>

#include "options.h"

using dyngi::sample::parseOptions;

namespace {
std::optional<dyngi::sample::Options> parse(std::vector<const char*> args, std::string& err) {
  args.insert(args.begin(), "dyngi_sample");
  return parseOptions(int(args.size()), args.data(), err);
}
}  // namespace

TEST(Options, DefaultsMatchTheContract) {
  std::string err;
  auto o = parse({}, err);
  ASSERT_TRUE(o);
  EXPECT_EQ(o->scene, "cornell-dynamic");
  EXPECT_EQ(o->width, 768u);
  EXPECT_EQ(o->height, 768u);
  EXPECT_EQ(o->gi, "off");
  EXPECT_FALSE(o->headless);
}

TEST(Options, ParsesEverything) {
  std::string err;
  auto o = parse({"--scene", "x.glb", "--headless", "--size", "320x200", "--frames", "7", "--gi", "off", "--out", "a.png",
                  "--hdr-out", "a.exr", "--stats", "s.json", "--exposure", "2.5"},
                 err);
  ASSERT_TRUE(o) << err;
  EXPECT_EQ(o->scene, "x.glb");
  EXPECT_TRUE(o->headless);
  EXPECT_EQ(o->width, 320u);
  EXPECT_EQ(o->height, 200u);
  EXPECT_EQ(o->frames, 7);
  EXPECT_EQ(o->out, "a.png");
  EXPECT_EQ(o->hdrOut, "a.exr");
  EXPECT_EQ(o->stats, "s.json");
  EXPECT_FLOAT_EQ(o->exposure, 2.5f);
}

TEST(Options, ParsesGiOptions) {
  std::string err;
  auto o = parse({"--gi", "bvh", "--temporal", "8", "--reshoot", "20", "--vpls", "1024", "--interleave", "2", "--clamp", "0.05",
                  "--animate", "moving-spot", "--vpl-source", "paths", "--voxel-res", "256", "--view", "voxels", "--seed", "7"},
                 err);
  ASSERT_TRUE(o) << err;
  EXPECT_EQ(o->gi, "bvh");
  EXPECT_EQ(o->temporal, 8u);
  EXPECT_EQ(o->reshoot, 20u);
  EXPECT_EQ(o->vpls, 1024u);
  EXPECT_EQ(o->interleave, 2u);
  EXPECT_FLOAT_EQ(o->distanceClamp, 0.05f);
  EXPECT_EQ(o->animate, "moving-spot");
  EXPECT_EQ(o->voxelResolution, 256u);
  EXPECT_EQ(o->view, "voxels");
  EXPECT_EQ(o->seed, 7u);
}

TEST(Options, WarmupFramesAreLeftOutOfTheMedians) {
  std::string err;
  auto o = parse({"--frames", "40", "--warmup", "18"}, err);
  ASSERT_TRUE(o) << err;
  EXPECT_EQ(o->warmupFrames(), 18);
  // Default: two, but a short run keeps one frame to time.
  EXPECT_EQ(parse({"--headless"}, err)->warmupFrames(), 2);
  EXPECT_EQ(parse({"--frames", "1"}, err)->warmupFrames(), 0);
  EXPECT_EQ(parse({"--frames", "2"}, err)->warmupFrames(), 1);
  EXPECT_EQ(parse({"--frames", "3"}, err)->warmupFrames(), 2);
}

TEST(Options, RejectsBadValuesClearly) {
  const std::vector<std::vector<const char*>> bad = {
      {"--gi", "magic"}, {"--size", "0x0"}, {"--size", "12"}, {"--size", "axb"}, {"--frames", "-3"},
      {"--frames"},      {"--bogus"},       {"--exposure", "nan"}, {"--exposure", "-1"},
      {"--temporal", "0"}, {"--temporal", "33"}, {"--animate", "dance"}, {"--vpl-source", "magic"},
      {"--vpls", "3"},   {"--interleave", "9"}, {"--clamp", "-1"}, {"--voxel-res", "100"}, {"--view", "xray"},
      {"--seed", "-4"},  {"--warmup", "x"},    {"--frames", "5", "--warmup", "5"}, {"--headless", "--warmup", "60"}};
  for (auto& args : bad) {
    std::string err;
    EXPECT_FALSE(parse(args, err)) << args[0];
    EXPECT_FALSE(err.empty());
    EXPECT_EQ(err.find('\n'), std::string::npos);
  }
  std::string err;
  parse({"--gi", "magic"}, err);
  EXPECT_NE(err.find("magic"), std::string::npos);
  EXPECT_NE(err.find("available"), std::string::npos);
}
