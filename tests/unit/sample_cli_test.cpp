// Runs the real sample binary on bad input: one clear line on stderr, exit code 2, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "options.h"
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
      {"--headless --view vpls", "is a view of --gi many-lights"},
      {"--headless --gi svo", "is now --gi temporal"},
      {"--headless --gi temporal --vpl-source rsm", "is now --gi many-lights"},
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

// --help lists every --gi mode, every flag of the sample's table and every option of every technique
// with its default, from the same tables the parser reads.
TEST(SampleCli, HelpListsEveryModeFlagAndOption) {
  dyngi::test::TempDir dir;
  const dyngi::test::SampleRun r = runSample("--help", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const std::string& mode : dyngi::sample::giModes()) EXPECT_NE(r.out.find(mode), std::string::npos) << mode;
  for (const char* flag : {"--scene PATH|NAME", "--size WxH", "--gi MODE", "--view NAME", "--stats FILE.json", "--help-markdown"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
  dyngi::gi::GiSettings defaults;
  for (const dyngi::gi::TechniqueEntry& e : dyngi::gi::techniqueRegistry())
    for (const dyngi::gi::OptionRef& o : e.options(defaults))
      EXPECT_NE(r.out.find(o.flag() + " "), std::string::npos) << e.name << " " << o.flag();
  EXPECT_NE(r.out.find("--visibility svo|bvh|none"), std::string::npos);
  EXPECT_NE(r.out.find("(default 768x768)"), std::string::npos);
}

// docs/OPTIONS.md is what --help-markdown prints: regenerate it with
//   build/bin/dyngi_sample --help-markdown > docs/OPTIONS.md
TEST(SampleCli, OptionsDocIsTheGeneratedOne) {
  dyngi::test::TempDir dir;
  const dyngi::test::SampleRun r = runSample("--help-markdown", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream f(DYNGI_OPTIONS_DOC);
  ASSERT_TRUE(f) << DYNGI_OPTIONS_DOC;
  std::stringstream committed;
  committed << f.rdbuf();
  EXPECT_EQ(committed.str(), r.out) << "docs/OPTIONS.md is stale: build/bin/dyngi_sample --help-markdown > docs/OPTIONS.md";
}
