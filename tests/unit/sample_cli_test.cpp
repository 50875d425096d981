// Runs the real sample binary on bad input: one clear line on stderr, exit code 2, never a crash.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "support/temp_dir.h"

namespace {
struct SampleRun {
  int exitCode = -1;
  std::string err;
};

SampleRun runSample(const std::string& args, const dyngi::test::TempDir& dir) {
  std::string errFile = dir.file("stderr.txt");
  std::string cmd = std::string(DYNGI_SAMPLE_EXE) + " " + args + " >/dev/null 2>" + errFile;
  int status = std::system(cmd.c_str());
  SampleRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream f(errFile);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  return r;
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
  };
  for (const Case& c : cases) {
    SampleRun r = runSample(c.args, dir);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
  }
}

TEST(SampleCli, HelpSucceeds) {
  dyngi::test::TempDir dir;
  EXPECT_EQ(runSample("--help", dir).exitCode, 0);
}
