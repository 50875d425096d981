// Runs the real sample binary on bad input: one clear line on stderr, exit code 2, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "support/sample_run.h"
#include "support/temp_dir.h"

namespace {
dyngi::test::SampleRun runSample(const std::string& args, const dyngi::test::TempDir& dir) {
  return dyngi::test::runSample(DYNGI_SAMPLE_EXE, args, dir);
}
}  // namespace

TEST(SampleCli, BadInputExitsWithCode2AndOneLine) {
  dyngi::test::TempDir dir;
  std::string malformed = dir.write("broken.gltf", "{ not json");
  std::string empty = dir.write("empty.gltf", R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[]}],"scene":0})");
  struct Case {
    std::string args, mentions;
  };
  const Case cases[] = {
      {"--headless --scene /no/such/file.glb", "file not found"},
      {"--headless --scene " + malformed, "not a valid glTF"},
      {"--headless --scene " + empty, "empty scene"},
      {"--gi unknown-mode", "unknown --gi mode"},
      {"--size 0x0", "--size"},
      {"--no-such-flag", "unknown option"},
      {"--headless --view vpls", "needs --gi svo --vpl-source rsm"},
      {"--headless --gi bvh --vpl-source rsm", "needs --gi svo"},
      // Output paths go where they point: no directory is made on the side, before any rendering.
      {"--headless --frames 1 --size 8x8 --out " + dir.file("no/such/dir/x.png"), "does not exist"},
      {"--headless --frames 1 --size 8x8 --hdr-out /no-such-root-dir/x.exr", "does not exist"},
      {"--headless --frames 1 --size 8x8 --stats " + dir.file(""), "is a directory"},
  };
  for (const Case& c : cases) {
    dyngi::test::SampleRun r = runSample(c.args, dir);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("no"))) << "a missing output directory was created";
}

TEST(SampleCli, HelpSucceeds) {
  dyngi::test::TempDir dir;
  EXPECT_EQ(runSample("--help", dir).exitCode, 0);
}
