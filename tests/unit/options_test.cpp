#include <gtest/gtest.h>

#include <set>

#include "dyngi/gi/options.h"
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
  auto o = parse({"--gi", "temporal", "--visibility", "bvh", "--temporal-sets", "8", "--reshoot-budget", "20", "--vpls", "1024",
                  "--interleave", "2", "--distance-clamp", "0.05", "--animate", "moving-spot", "--voxel-resolution", "256", "--view",
                  "voxels", "--seed", "7"},
                 err);
  ASSERT_TRUE(o) << err;
  EXPECT_EQ(o->gi, "temporal");
  const dyngi::gi::GiSettings& g = o->giSettings;
  EXPECT_EQ(g.technique, "temporal");
  EXPECT_EQ(g.temporal.visibility, dyngi::gi::VisibilityBackend::Bvh);
  EXPECT_EQ(g.temporal.temporalSets, 8u);
  EXPECT_EQ(g.temporal.reshootBudget, 20u);
  EXPECT_EQ(g.temporal.vpl.vpls, 1024u);
  EXPECT_EQ(g.temporal.vpl.interleave, 2u);
  EXPECT_FLOAT_EQ(g.temporal.vpl.distanceClamp, 0.05f);
  EXPECT_EQ(o->animate, "moving-spot");
  EXPECT_EQ(g.voxels.resolution, 256u);
  EXPECT_EQ(o->view, "voxels");
  EXPECT_EQ(g.temporal.vpl.seed, 7u);
}

// Every GI setting travels from the command line into the one options struct the technique reads,
// and a default is the struct's member initializer: nothing in the sample restates it.
TEST(Options, GiSettingsComeFromTheTechniquesTables) {
  std::string err;
  auto o = parse({"--gi", "many-lights", "--vpls", "2048", "--bounces", "3", "--rsm-resolution", "128", "--visibility", "none"}, err);
  ASSERT_TRUE(o) << err;
  EXPECT_EQ(o->giSettings.technique, "many-lights");
  EXPECT_EQ(o->giSettings.manyLights.vpl.vpls, 2048u);
  EXPECT_EQ(o->giSettings.manyLights.vpl.bounces, 3u);
  EXPECT_EQ(o->giSettings.manyLights.rsmResolution, 128u);
  EXPECT_EQ(o->giSettings.manyLights.visibility, dyngi::gi::VisibilityBackend::None);
  // Untouched values are the structs' defaults.
  auto d = parse({"--gi", "temporal"}, err);
  ASSERT_TRUE(d) << err;
  EXPECT_EQ(d->giSettings.temporal.vpl.vpls, dyngi::gi::VplOptions{}.vpls);
  EXPECT_EQ(d->giSettings.temporal.visibility, dyngi::gi::VisibilityBackend::Svo);
  EXPECT_EQ(d->giSettings.temporal.temporalSets, dyngi::gi::TemporalOptions{}.temporalSets);
  EXPECT_EQ(d->giSettings.budget.budgetMs, 0.0f) << "no GI budget unless asked for";
  auto b = parse({"--gi", "vct", "--gi-budget-ms", "12.5"}, err);
  ASSERT_TRUE(b) << err;
  EXPECT_EQ(b->giSettings.budget.budgetMs, 12.5f);
  auto p = parse({"--gi", "path", "--spp", "9", "--bounces", "12", "--seed", "3"}, err);
  ASSERT_TRUE(p) << err;
  EXPECT_EQ(p->pathTracer.spp, 9u);
  EXPECT_EQ(p->pathTracer.bounces, 12u);
  EXPECT_EQ(p->pathTracer.seed, 3u);
}

TEST(Options, ATableOptionOutsideItsRangeOrTechniqueIsOneClearLine) {
  struct Case {
    std::vector<const char*> args;
    const char* mentions;
  };
  const Case cases[] = {
      {{"--gi", "temporal", "--vpls", "3"}, "--vpls wants an integer in 16..65536, got '3'"},
      {{"--gi", "temporal", "--bounces", "4"}, "--bounces wants an integer in 1..3"},
      {{"--gi", "path", "--bounces", "65"}, "--bounces wants an integer in 0..64"},
      {{"--gi", "temporal", "--voxel-resolution", "100"}, "--voxel-resolution wants a power of two in 64..512"},
      {{"--gi", "temporal", "--distance-clamp", "nan"}, "--distance-clamp wants a number in 0..100"},
      {{"--gi", "temporal", "--incremental-accumulation", "maybe"}, "--incremental-accumulation wants on or off"},
      {{"--gi", "temporal", "--visibility", "rays"}, "--visibility wants one of svo, bvh, none, got 'rays'"},
      {{"--gi", "many-lights", "--visibility", "bvh"}, "--visibility wants one of svo, none, got 'bvh'"},
      {{"--gi", "temporal", "--rsm-resolution", "256"}, "--rsm-resolution is an option of --gi many-lights, not of --gi temporal"},
      {{"--gi", "off", "--vpls", "64"}, "--vpls is an option of --gi temporal|many-lights"},
      {{"--gi", "temporal", "--spp", "4"}, "--spp is an option of --gi path"},
      {{"--gi", "temporal", "--vpls"}, "--vpls needs a value"},
      {{"--gi", "temporal", "--view", "vpls"}, "--view vpls is a view of --gi many-lights, not of --gi temporal"},
      {{"--gi", "off", "--view", "indirect"}, "--view indirect needs a GI technique (--gi temporal|many-lights|vct)"},
      {{"--gi", "temporal", "--gi-budget-ms", "-1"}, "--gi-budget-ms wants a number in 0..10000"},
      {{"--gi", "path", "--gi-budget-ms", "10"}, "--gi-budget-ms is an option of --gi temporal|many-lights|vct, not of --gi path"},
  };
  for (const Case& c : cases) {
    std::string err;
    EXPECT_FALSE(parse(c.args, err)) << c.mentions;
    EXPECT_NE(err.find(c.mentions), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  }
}

// --help is generated from the tables: every option of every technique appears with its default.
TEST(Options, HelpListsEveryTableOptionWithItsDefault) {
  const std::string help = dyngi::sample::usage();
  dyngi::gi::GiSettings defaults;
  for (const dyngi::gi::TechniqueEntry& e : dyngi::gi::techniqueRegistry()) {
    EXPECT_NE(help.find(std::string("--gi ") + e.name + ": " + e.summary), std::string::npos) << e.name;
    for (const dyngi::gi::OptionRef& r : e.options(defaults)) {
      const std::string flag = std::string("--") + r.spec->name + " ";
      EXPECT_NE(help.find(flag), std::string::npos) << flag;
      EXPECT_NE(help.find(r.spec->help), std::string::npos) << flag;
    }
  }
  EXPECT_NE(help.find("VPLs over all bounces (rounded down to a multiple of the bounces) (default 512, 16..65536)"), std::string::npos)
      << help;
}

// The spellings the command line used to take are refused with one line naming the one that replaced
// them, so a script written for them fails loudly instead of running something else.
TEST(Options, OldSpellingsAreRefusedNamingTheNewOne) {
  struct Case {
    std::vector<const char*> args;
    const char* names;
  };
  const Case cases[] = {
      {{"--gi", "svo"}, "--gi temporal"},
      {{"--gi", "bvh"}, "--gi temporal --visibility bvh"},
      {{"--gi", "temporal", "--vpl-source", "rsm"}, "--gi many-lights"},
      {{"--gi", "temporal", "--temporal", "8"}, "--temporal-sets"},
      {{"--gi", "temporal", "--reshoot", "8"}, "--reshoot-budget"},
      {{"--gi", "temporal", "--clamp", "0.1"}, "--distance-clamp"},
      {{"--gi", "many-lights", "--rsm-res", "64"}, "--rsm-resolution"},
      {{"--gi", "many-lights", "--indirect-shadows", "0"}, "--visibility svo|none"},
      {{"--gi", "vct", "--cones", "6"}, "--diffuse-cones"},
      {{"--gi", "vct", "--diffuse-filter", "2"}, "--diffuse-filter-radius"},
      {{"--voxel-res", "64"}, "--voxel-resolution"},
  };
  for (const Case& c : cases) {
    std::string err;
    EXPECT_FALSE(parse(c.args, err)) << c.names;
    EXPECT_NE(err.find(std::string("is now ") + c.names), std::string::npos) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  }
}

// A table option's flag is its member's name with dashes, after the table's prefix.
TEST(OptionTable, AFlagIsItsMembersName) {
  EXPECT_EQ(dyngi::gi::optionName("", "vpls"), "vpls");
  EXPECT_EQ(dyngi::gi::optionName("", "temporalSets"), "temporal-sets");
  EXPECT_EQ(dyngi::gi::optionName("", "coneStep"), "cone-step");
  EXPECT_EQ(dyngi::gi::optionName("voxel", "resolution"), "voxel-resolution");
  EXPECT_EQ(dyngi::gi::optionName("gi", "budgetMs"), "gi-budget-ms");
  dyngi::gi::GiSettings s;
  EXPECT_TRUE(dyngi::gi::findOption(dyngi::gi::bindOptions(s.vct), "diffuse-filter-radius"));
  EXPECT_TRUE(dyngi::gi::findOption(dyngi::gi::bindOptions(s.temporal), "incremental-accumulation"));
}

TEST(Options, EveryGiModeIsOffATechniqueOrThePathTracer) {
  const std::vector<std::string>& modes = dyngi::sample::giModes();
  ASSERT_EQ(modes.size(), dyngi::gi::techniqueRegistry().size() + 2);
  EXPECT_EQ(modes.front(), "off");
  EXPECT_EQ(modes.back(), "path");
  for (const dyngi::gi::TechniqueEntry& e : dyngi::gi::techniqueRegistry()) {
    std::string err;
    auto o = parse({"--gi", e.name, "--view", "indirect"}, err);
    ASSERT_TRUE(o) << e.name << ": " << err;
    EXPECT_EQ(o->giSettings.technique, e.name);
    EXPECT_TRUE(o->usesGiSystem());
    for (const char* view : e.debugViews) EXPECT_TRUE(parse({"--gi", e.name, "--view", view}, err)) << err;
  }
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
      {"--gi", "temporal", "--temporal-sets", "0"}, {"--gi", "temporal", "--temporal-sets", "33"}, {"--animate", "dance"},
      {"--gi", "temporal", "--vpls", "3"}, {"--gi", "temporal", "--interleave", "9"}, {"--gi", "temporal", "--distance-clamp", "-1"},
      {"--voxel-resolution", "100"}, {"--view", "xray"},
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

TEST(OptionTable, ParsesChecksAndReportsAdjustedValues) {
  struct Knobs {
    uint32_t count = 8;
    float scale = 0.5f;
    bool on = true;
    uint32_t size = 64;
    static const dyngi::gi::OptionTable<Knobs>& table() {
      static const auto t = dyngi::gi::OptionTable<Knobs>()
                                .add(DYNGI_OPTION(Knobs, count), "how many", 1, 100)
                                .add(DYNGI_OPTION(Knobs, scale), "how much", 0, 2)
                                .add(DYNGI_OPTION(Knobs, on), "whether", 0, 1)
                                .add(DYNGI_OPTION(Knobs, size), "how big", 16, 256, true);
      return t;
    }
  };
  Knobs k;
  auto refs = dyngi::gi::bindOptions(k);
  ASSERT_EQ(refs.size(), 4u);
  EXPECT_EQ(dyngi::gi::parseOptionValue(refs[0], "42"), "");
  EXPECT_EQ(k.count, 42u);
  EXPECT_NE(dyngi::gi::parseOptionValue(refs[0], "101"), "");
  EXPECT_NE(dyngi::gi::parseOptionValue(refs[0], "4x"), "");
  EXPECT_EQ(k.count, 42u) << "a rejected value leaves the option as it was";
  EXPECT_EQ(dyngi::gi::parseOptionValue(refs[1], "1.25"), "");
  EXPECT_FLOAT_EQ(k.scale, 1.25f);
  EXPECT_NE(dyngi::gi::parseOptionValue(refs[1], "inf"), "");
  EXPECT_EQ(dyngi::gi::parseOptionValue(refs[2], "off"), "");
  EXPECT_FALSE(k.on);
  EXPECT_NE(dyngi::gi::parseOptionValue(refs[3], "100"), "") << "not a power of two";
  EXPECT_EQ(dyngi::gi::parseOptionValue(refs[3], "128"), "");
  EXPECT_EQ(k.size, 128u);
  Knobs used = k;
  used.count = 40;
  const auto lines = dyngi::gi::adjustedOptions(dyngi::gi::bindOptions(k), dyngi::gi::bindOptions(used));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "--count 42 is used as 40");
}

// Every option table keeps the rules the command line, --help and a settings panel rely on: names are
// unique within a technique and valid flags, each has help, and each default lies in its own range.
TEST(OptionTable, EveryTableIsWellFormedAndItsDefaultsLieInTheirRanges) {
  auto check = [](const std::vector<dyngi::gi::OptionRef>& refs, const std::string& owner) {
    std::set<std::string> names;
    for (const dyngi::gi::OptionRef& r : refs) {
      const std::string name = r.spec->name;
      EXPECT_TRUE(names.insert(name).second) << owner << ": --" << name << " twice";
      EXPECT_FALSE(name.empty()) << owner;
      EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-"), std::string::npos) << owner << ": --" << name;
      EXPECT_GT(std::string(r.spec->help).size(), 5u) << owner << ": --" << name << " has no help";
      EXPECT_LE(r.spec->min, r.spec->max) << owner << ": --" << name;
      EXPECT_GE(r.get(), r.spec->min) << owner << ": --" << name << " default below its range";
      EXPECT_LE(r.get(), r.spec->max) << owner << ": --" << name << " default above its range";
      // The default survives a round trip through its own text, as the command line would give it.
      const double before = r.get();
      EXPECT_EQ(dyngi::gi::parseOptionValue(r, r.text()), "") << owner << ": --" << name;
      EXPECT_EQ(r.get(), before) << owner << ": --" << name;
    }
  };
  dyngi::gi::GiSettings settings;
  for (const dyngi::gi::TechniqueEntry& e : dyngi::gi::techniqueRegistry()) check(e.options(settings), e.name);
  dyngi::gi::PathTracerSettings pt;
  check(dyngi::gi::bindOptions(pt), "path tracer");
  check(dyngi::gi::bindOptions(settings.voxels), "voxels");
}
