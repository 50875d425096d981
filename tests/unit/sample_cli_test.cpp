// Runs the real sample binary on bad input: one clear line on stderr, exit code 2, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>

#include <stb_image.h>

#include "dyngi/engine/scene/components.h"
#include "options.h"
#include "support/gltf_writer.h"
#include "support/hostile_content.h"
#include "support/sample_run.h"
#include "support/temp_dir.h"

namespace {
dyngi::test::SampleRun runSample(const std::string& args, const dyngi::test::TempDir& dir, int timeoutSeconds = 120) {
  return dyngi::test::runSample(DYNGI_SAMPLE_EXE, args, dir, timeoutSeconds);
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
      {"--frame-budget-ms -5", "--frame-budget-ms"},
      {"--frame-budget-ms nan", "--frame-budget-ms"},
      {"--no-such-flag", "unknown option"},
      {"--headless --view vpls", "is a view of --gi many-lights"},
      {"--headless --gi svo", "is now --gi temporal"},
      {"--headless --gi temporal --vpl-source rsm", "is now --gi many-lights"},
      // Output paths go where they point: no directory is made on the side, before any rendering.
      {"--headless --frames 1 --size 8x8 --out " + dir.file("no/such/dir/x.png"), "does not exist"},
      {"--headless --frames 1 --size 8x8 --hdr-out /no-such-root-dir/x.exr", "does not exist"},
      {"--headless --frames 1 --size 8x8 --stats " + dir.file(""), "is a folder"},
  };
  for (const Case& c : cases) {
    dyngi::test::SampleRun r = runSample(c.args, dir);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("no"))) << "a missing output directory was created";
}

// Special files and long or broken names (docs/CONTENT.md): refused before anything renders, exit 2, one
// line, never a hang on a FIFO or a read of /dev/zero until memory runs out.
TEST(SampleCli, SpecialFilesAndBadNamesAreRefusedBeforeRendering) {
  dyngi::test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("fifo").c_str(), 0600), 0);
  const std::string longName = dir.file(std::string(300, 'n') + ".png");
  const std::string missingShot = dir.write("shot.txt", "2 screenshot " + dir.file("no/such/dir/s.png") + "\n3 quit\n");
  const std::string binary = dir.write("binary.txt", std::string("1 \x01\x02\x1b[2J\x7f\n", 9));
  const std::string hugeToken = dir.write("huge.txt", "1 " + std::string(1 << 20, 'k') + "\n");
  struct Case {
    std::string args, mentions;
  };
  const Case cases[] = {
      {"--headless --frames 1 --size 8x8 --out " + dir.file("fifo"), "is a FIFO"},
      {"--headless --frames 1 --size 8x8 --stats " + dir.file("fifo"), "is a FIFO"},
      {"--headless --frames 1 --size 8x8 --out " + longName, "longer than 255 characters"},
      {"--headless --frames 1 --size 8x8 --out " + dir.file(std::string(5000, 'n')), "longer than 4095 characters"},
      {"--headless --frames 1 --size 8x8 --scene " + dir.file("fifo"), "is a FIFO, not a regular file"},
      {"--headless --frames 1 --size 8x8 --input-script " + dir.file("fifo"), "is a FIFO"},
      {"--headless --frames 1 --size 8x8 --input-script /dev/zero", "is a character device"},
      {"--headless --frames 1 --size 8x8 --input-script " + dir.file(""), "is a folder"},
      {"--headless --frames 1 --size 8x8 --input-script " + missingShot, "does not exist"},
      {"--headless --frames 1 --size 8x8 --input-script " + binary, "\\x1b[2J"},
      {"--headless --frames 1 --size 8x8 --input-script " + hugeToken, "..."},
      {"--headless --frames 1 --size 8x8 --scene \"$(printf '" + dir.file("a") + "\\nb.gltf')\"", "a\\nb.gltf"},
  };
  for (const Case& c : cases) {
    dyngi::test::SampleRun r = runSample(c.args, dir, 30);
    EXPECT_EQ(r.exitCode, 2) << c.args.substr(0, 200) << "\n" << r.err.substr(0, 400);
    EXPECT_NE(r.err.find(c.mentions), std::string::npos) << c.args.substr(0, 200) << ": " << r.err.substr(0, 400);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args.substr(0, 200) << ": " << r.err.substr(0, 400);
    EXPECT_LT(r.err.size(), 1100u) << c.args.substr(0, 200);
  }
}

// A full disk is an error for every output kind: exit 1 naming the file, never "wrote".
TEST(SampleCli, AFullDiskFailsEveryOutput) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  dyngi::test::TempDir dir;
  for (const char* flag : {"--out", "--hdr-out", "--stats", "--memory-log"}) {
    dyngi::test::SampleRun r = runSample(std::string("--headless --frames 1 --size 8x8 ") + flag + " /dev/full", dir, 60);
    EXPECT_EQ(r.exitCode, 1) << flag << ": " << r.err;
    EXPECT_NE(r.err.find("/dev/full: could not be written"), std::string::npos) << flag << ": " << r.err;
    EXPECT_EQ(r.out.find("wrote /dev/full"), std::string::npos) << flag << ": " << r.out;
  }
}

// The brightest light the content rules allow saturates to white in every technique: no inf / inf in the
// tone map (black), no NaN in the GI (magenta).
// Under strace, a scene whose URIs point outside its folder (relative, percent-encoded, absolute, a
// buffer, a name that exists only in the working directory) never opens the file outside.
TEST(SampleCli, UrisOutsideTheScenesFolderAreNeverOpened) {
  if (std::system("strace -V >/dev/null 2>&1") != 0) GTEST_SKIP() << "strace is not installed (scripts/setup.sh installs it)";
  dyngi::test::TempDir dir;
  std::filesystem::create_directories(dir.file("scene"));
  const std::vector<uint8_t> png = dyngi::test::smallPng();
  dir.write("outside.png", std::string(png.begin(), png.end()));
  dir.write("outside.bin", std::string(64, '\0'));
  std::vector<std::string> scenes;
  for (const std::string& uri : {std::string("../outside.png"), std::string("%2e%2e/outside.png"), std::string("..%2Foutside.png"),
                                 dir.file("outside.png"), std::string("outside.png")}) {
    dyngi::test::GltfSpec s = dyngi::test::texturedQuad();
    s.imagesJson = {"{\"uri\":\"" + uri + "\"}"};
    scenes.push_back(dir.write("scene/image" + std::to_string(scenes.size()) + ".gltf", dyngi::test::writeGltf(s)));
  }
  std::string text = dyngi::test::writeGltf(dyngi::test::texturedQuad());
  const size_t data = text.find("\"uri\":\"data:application/octet-stream");
  ASSERT_NE(data, std::string::npos);
  text.replace(data, text.find('"', data + 7) - data + 1, "\"uri\":\"../outside.bin\"");
  scenes.push_back(dir.write("scene/buffer.gltf", text));
  for (const std::string& scene : scenes) {
    const std::string trace = dir.file("trace.txt");
    // Run from the folder that holds outside.png, so a working-directory fallback would find it.
    // LeakSanitizer cannot run under ptrace: the sanitizer build checks leaks everywhere but here.
    const std::string strace = "env -C " + dir.file("") + " ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\"" +
                               " strace -f -qq -e trace=open,openat,openat2,creat -o " + trace + " " DYNGI_SAMPLE_EXE;
    const dyngi::test::SampleRun r = runSample(strace, "--headless --frames 1 --size 16x16 --gi off --scene " + scene, dir);
    EXPECT_EQ(r.exitCode, 2) << scene << ": " << r.err;
    std::ifstream f(trace);
    std::stringstream opened;
    opened << f.rdbuf();
    ASSERT_NE(opened.str().find("openat"), std::string::npos) << "strace recorded nothing for " << scene;
    for (const char* outside : {"outside.png", "outside.bin"})
      EXPECT_EQ(opened.str().find(outside), std::string::npos) << scene << " opened " << outside;
  }
}

TEST(SampleCli, TheBrightestLightAllowedSaturatesWithoutNaN) {
  dyngi::test::TempDir dir;
  std::ifstream in(DYNGI_ASSETS_DIR "/cornell_box.gltf");
  std::stringstream text;
  text << in.rdbuf();
  std::string gltf = text.str();
  const size_t at = gltf.find("\"intensity\":6");
  ASSERT_NE(at, std::string::npos);
  gltf.replace(at, 13, "\"intensity\":" + std::to_string(int64_t(dyngi::scene::kMaxLightIntensity)));
  const std::string scene = dir.write("bright.gltf", gltf);
  for (const char* gi : {"off", "temporal", "vct"}) {
    const std::string png = dir.file(std::string(gi) + ".png");
    dyngi::test::SampleRun r = runSample("--headless --frames 3 --size 32x32 --gi " + std::string(gi) + " --scene " + scene + " --out " + png, dir);
    ASSERT_EQ(r.exitCode, 0) << gi << ": " << r.err;
    int w = 0, h = 0, n = 0;
    unsigned char* p = stbi_load(png.c_str(), &w, &h, &n, 3);
    ASSERT_NE(p, nullptr);
    int white = 0, magenta = 0;
    for (int i = 0; i < w * h; ++i) {
      const unsigned char* c = p + 3 * i;
      white += c[0] > 250 && c[1] > 250 && c[2] > 250;
      magenta += c[0] > 250 && c[1] < 5 && c[2] > 250;
    }
    stbi_image_free(p);
    EXPECT_EQ(magenta, 0) << gi;
    // Direct light alone leaves the shadowed ceiling and box sides dark; the GI lights them too.
    const int saturated = std::string(gi) == "off" ? w * h / 8 : w * h / 4;
    EXPECT_GT(white, saturated) << gi << ": the lit floor and walls saturate";
  }
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
