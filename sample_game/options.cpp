#include "dyngi/engine/platform/files.h"
#include "options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <vector>

#include "scenes/builtin_scenes.h"

namespace dyngi::sample {

const std::vector<std::string>& giModes() {
  static const std::vector<std::string> modes = [] {
    std::vector<std::string> m = {"off"};
    for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) m.push_back(e.name);
    m.push_back("path");
    return m;
  }();
  return modes;
}

bool isTechniqueMode(std::string_view mode) { return gi::findTechnique(mode) != nullptr; }

const std::vector<std::string>& commonGiViews() {
  static const std::vector<std::string> views = {"final", "indirect"};
  return views;
}

const std::vector<std::string>& voxelViews() {
  static const std::vector<std::string> views = {"voxels", "svo-steps"};
  return views;
}

namespace {

std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : separator) + n;
  return s;
}

bool contains(const std::vector<std::string>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool parseUint(const std::string& s, uint32_t& out) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// One of the sample's own flags. A value's default is the Options member's initializer; `shown` reads
// it back for --help.
struct SampleFlag {
  const char* name;     // without the dashes
  const char* value;    // what it takes, for --help ("" for a switch)
  const char* help;
  std::function<std::string(Options&, const std::string&)> set;  // an error line, or ""
  std::function<std::string(const Options&)> shown = {};         // the value as text (none: no default shown)
};

std::string oneOf(const char* flag, const std::vector<std::string>& names, const std::string& v, std::string& into) {
  if (!contains(names, v)) return "unknown " + std::string(flag) + " '" + v + "' (available: " + joined(names, ", ") + ")";
  into = v;
  return {};
}

std::string count(const char* flag, const std::string& v, uint32_t min, int& into) {
  uint32_t n = 0;
  if (!parseUint(v, n) || n < min || n > 1000000)
    return std::string(flag) + " wants " + (min > 0 ? "a positive integer" : "a frame count") + ", got '" + v + "'";
  into = int(n);
  return {};
}

std::string sizeOf(Options& o, const std::string& v) {
  const size_t x = v.find('x');
  if (x == std::string::npos || !parseUint(v.substr(0, x), o.width) || !parseUint(v.substr(x + 1), o.height) || o.width == 0 ||
      o.height == 0 || o.width > 8192 || o.height > 8192)
    return "--size wants WxH with 1..8192 each, got '" + v + "'";
  return {};
}

std::string exposureOf(Options& o, const std::string& v) {
  float f = 0;
  auto r = std::from_chars(v.data(), v.data() + v.size(), f);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(f) || f <= 0)
    return "--exposure wants a positive number, got '" + v + "'";
  o.exposure = f;
  return {};
}

std::string frameBudgetOf(Options& o, const std::string& v) {
  float f = 0;
  auto r = std::from_chars(v.data(), v.data() + v.size(), f);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(f) || f < 0 || f > 10000)
    return "--frame-budget-ms wants milliseconds in 0..10000, got '" + v + "'";
  o.frameBudgetMs = f;
  return {};
}

std::function<std::string(Options&, const std::string&)> into(std::string Options::*member) {
  return [member](Options& o, const std::string& v) { return (o.*member = v), std::string(); };
}
std::function<std::string(Options&, const std::string&)> on(bool Options::*member) {
  return [member](Options& o, const std::string&) { return (o.*member = true), std::string(); };
}
std::function<std::string(const Options&)> text(std::string Options::*member) {
  return [member](const Options& o) { return o.*member; };
}

const std::vector<SampleFlag>& sampleFlags() {
  static const std::vector<SampleFlag> flags = {
      {"scene", "PATH|NAME", "a .gltf/.glb file or a built-in scene (showcase: an uplight, mostly bounce light; cornell-emissive: lit by an emissive quad only; two-rooms[-door]: the leak test)",
       [](Options& o, const std::string& v) { return (o.scene = v), std::string(); }, text(&Options::scene)},
      {"headless", "", "render offscreen, no window (also the fallback when no window opens)", on(&Options::headless)},
      {"size", "WxH", "render size",
       sizeOf, [](const Options& o) { return std::to_string(o.width) + "x" + std::to_string(o.height); }},
      {"frames", "N", "frames to render (default: 60 headless, until closed in a window)",
       [](Options& o, const std::string& v) { return count("--frames", v, 1, o.frames); }},
      {"gi", "MODE", "global illumination: off, a technique (its options below) or path (the reference path tracer)",
       [](Options& o, const std::string& v) { return oneOf("--gi mode", giModes(), v, o.gi); }, text(&Options::gi)},
      {"animate", "NAME", "a scripted scene: the Cornell box with a moving spot, object or camera, the glTF fox, or a flight down the street (benchmark and soak scenes)",
       [](Options& o, const std::string& v) { return oneOf("--animate", animatedSceneNames(), v, o.animate); }},
      {"view", "NAME", "final, indirect (the GI's diffuse light before albedo), voxels, svo-steps, or a technique's view (below)",
       into(&Options::view), text(&Options::view)},
      {"out", "FILE.png", "write the last frame, tone-mapped sRGB", into(&Options::out)},
      {"hdr-out", "FILE.exr", "write the last frame's linear radiance before exposure", into(&Options::hdrOut)},
      {"stats", "FILE.json", "write timings (medians after the warm-up), counts and the settings used", into(&Options::stats)},
      {"memory-log", "FILE.tsv", "every 100 frames: frame, resident memory, live Vulkan allocations, device bytes", into(&Options::memoryLog)},
      {"warmup", "N", "frames left out of the --stats medians (default 2, fewer for shorter runs)",
       [](Options& o, const std::string& v) { return count("--warmup", v, 0, o.warmup); }},
      {"stage-times", "timestamps|fenced", "how --stats times each pass: GPU timestamps, or the CPU clock between fences at each pass' ends",
       [](Options& o, const std::string& v) { return oneOf("--stage-times", {"timestamps", "fenced"}, v, o.stageTimes); },
       text(&Options::stageTimes)},
      {"clip", "NAME", "glTF animation clip to play (default: the first)", into(&Options::clip)},
      {"ui", "on|off|auto", "the settings panel (auto: in a window, not headless)",
       [](Options& o, const std::string& v) { return oneOf("--ui", {"on", "off", "auto"}, v, o.ui); }, text(&Options::ui)},
      {"input-script", "FILE", "replay clicks, drags, keys and panel clicks from FILE (format: sample_game/play/input.h), fixed time step",
       into(&Options::inputScript)},
      {"record", "DIR", "write every frame's displayed image to DIR/frame_NNNNN.png", into(&Options::recordDir)},
      {"exposure", "X", "linear exposure multiplier", exposureOf,
       [](const Options& o) {
         char b[32];
         std::snprintf(b, sizeof b, "%g", double(o.exposure));
         return std::string(b);
       }},
      {"frame-budget-ms", "X",
       "hold the whole frame near X ms by giving the GI budget what the rest of the frame leaves (0: off; default 100 in a window "
       "without --gi-budget-ms or --input-script, else off)",
       frameBudgetOf},
      {"validation", "", "enable the Vulkan validation layer (missing: an error)", on(&Options::validation)},
      {"help", "", "this text", on(&Options::help)},
      {"help-markdown", "", "every option as Markdown (docs/OPTIONS.md)", on(&Options::helpMarkdown)},
  };
  return flags;
}

const SampleFlag* findSampleFlag(std::string_view name) {
  for (const SampleFlag& f : sampleFlags())
    if (name == f.name) return &f;
  return nullptr;
}

// Spellings the command line no longer takes, each with the one that replaced it.
std::string renamedSpelling(const std::string& flag, const std::string* value) {
  static const std::pair<const char*, const char*> renamed[] = {
      {"--vpl-source", "--gi many-lights (rsm) or --gi temporal (paths)"},
      {"--temporal", "--temporal-sets"},
      {"--reshoot", "--reshoot-budget"},
      {"--incremental", "--incremental-accumulation"},
      {"--clamp", "--distance-clamp"},
      {"--rsm-res", "--rsm-resolution"},
      {"--indirect-shadows", "--visibility svo|none"},
      {"--cones", "--diffuse-cones"},
      {"--diffuse-filter", "--diffuse-filter-radius"},
      {"--voxel-res", "--voxel-resolution"},
  };
  if (flag == "--gi" && value && (*value == "svo" || *value == "bvh"))
    return "--gi " + *value + " is now --gi temporal" + (*value == "bvh" ? " --visibility bvh" : " (--visibility svo is its default)");
  if (flag == "--gi" && value && *value == "rsm") return "--gi rsm is now --gi many-lights";
  for (const auto& [old, now] : renamed)
    if (flag == old) return flag + " is now " + now;
  return {};
}

void append(std::vector<gi::OptionRef>& to, std::vector<gi::OptionRef> from) { to.insert(to.end(), from.begin(), from.end()); }

// Every table option this run can take: the technique's and the budget's, the path tracer's (--gi
// path), the voxel scene's.
std::vector<gi::OptionRef> acceptedOptions(Options& o) {
  std::vector<gi::OptionRef> refs;
  if (const gi::TechniqueEntry* e = gi::findTechnique(o.gi)) {
    append(refs, e->options(o.giSettings));
    append(refs, gi::bindOptions(o.giSettings.budget));
  }
  if (o.gi == "path") append(refs, gi::bindOptions(o.pathTracer));
  append(refs, gi::bindOptions(o.giSettings.voxels));
  return refs;
}

// The error for a table option this run does not take: which --gi it belongs to, when any.
std::string notForThisRun(const Options& o, const std::string& flag) {
  const std::string name = flag.substr(2);
  gi::GiSettings probe;
  std::vector<std::string> owners;
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry())
    if (gi::findOption(e.options(probe), name)) owners.push_back(e.name);
  if (gi::findOption(gi::bindOptions(probe.budget), name))
    for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) owners.push_back(e.name);
  gi::PathTracerSettings pt;
  if (gi::findOption(gi::bindOptions(pt), name)) owners.push_back("path");
  if (owners.empty()) return "unknown option '" + flag + "' (see --help)";
  return flag + " is an option of --gi " + joined(owners, "|") + ", not of --gi " + o.gi;
}

// Table options wait until --gi is known: it says which tables apply.
using Deferred = std::vector<std::pair<std::string, std::optional<std::string>>>;

std::string parseArguments(const std::vector<std::string>& args, Options& o, Deferred& deferred) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const std::string* next = i + 1 < args.size() ? &args[i + 1] : nullptr;
    if (std::string old = renamedSpelling(a, next); !old.empty()) return old;
    const SampleFlag* flag = a == "-h" ? findSampleFlag("help") : a.rfind("--", 0) == 0 ? findSampleFlag(a.substr(2)) : nullptr;
    if (flag) {
      if (*flag->value && !next) return a + " needs a value";
      if (std::string error = flag->set(o, *flag->value ? *next : std::string()); !error.empty()) return error;
      if (*flag->value) ++i;
    } else if (a.rfind("--", 0) == 0 && a.size() > 2) {
      deferred.emplace_back(a, next ? std::optional<std::string>(*next) : std::nullopt);
      if (next) ++i;
    } else {
      return "unknown option '" + a + "' (see --help)";
    }
  }
  return {};
}

std::string applyTableOptions(Options& o, const Deferred& deferred) {
  const std::vector<gi::OptionRef> accepted = acceptedOptions(o);
  for (const auto& [flag, value] : deferred) {
    const std::optional<gi::OptionRef> option = gi::findOption(accepted, flag.substr(2));
    if (!option) return notForThisRun(o, flag);
    if (!value) return flag + " needs a value";
    if (std::string error = gi::parseOptionValue(*option, *value); !error.empty()) return error;
  }
  return {};
}

// --view: a common view with a technique, a voxel view with any --gi, or the technique's own.
std::string checkView(const Options& o) {
  if (contains(voxelViews(), o.view) || o.view == "final") return {};
  const gi::TechniqueEntry* active = gi::findTechnique(o.gi);
  if (contains(commonGiViews(), o.view)) {
    if (active) return {};
    std::vector<std::string> techniques;
    for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) techniques.push_back(e.name);
    return "--view " + o.view + " needs a GI technique (--gi " + joined(techniques, "|") + ")";
  }
  if (active && std::find(active->debugViews.begin(), active->debugViews.end(), o.view) != active->debugViews.end()) return {};
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry())
    for (const char* v : e.debugViews)
      if (o.view == v) return "--view " + o.view + " is a view of --gi " + e.name + ", not of --gi " + o.gi;
  return "unknown --view '" + o.view + "' (see --help for each technique's views)";
}

std::string sampleFlagColumn(const SampleFlag& f) { return std::string("--") + f.name + (*f.value ? " " + std::string(f.value) : ""); }

// A Markdown table cell: a '|' would end it, inside code spans too.
std::string markdownCell(std::string_view text) {
  std::string cell;
  for (char c : text) cell += c == '|' ? std::string("\\|") : std::string(1, c);
  return cell;
}

}  // namespace

std::string usage() {
  std::string u = "usage: dyngi_sample [options]\n";
  const Options defaults;
  for (const SampleFlag& f : sampleFlags()) {
    std::string line = "  " + sampleFlagColumn(f);
    line.resize(std::max<size_t>(41, line.size() + 1), ' ');
    u += line + f.help + (f.shown ? " (default " + f.shown(defaults) + ")" : "") + "\n";
  }
  u += "  --gi takes: " + joined(giModes(), ", ") + "; --scene NAME: " + joined(builtinSceneNames(), ", ") +
       "; --animate: " + joined(animatedSceneNames(), ", ") + "\n";
  gi::GiSettings settings;
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    u += "\n--gi " + std::string(e.name) + ": " + e.summary + "\n";
    if (!e.debugViews.empty()) {
      u += "  views: final indirect";
      for (const char* v : e.debugViews) u += std::string(" ") + v;
      u += "\n";
    }
    u += gi::optionHelp(e.options(settings));
  }
  gi::PathTracerSettings pt;
  u += "\n--gi path: the reference path tracer (CPU)\n" + gi::optionHelp(gi::bindOptions(pt));
  u += "\nVoxel scene (techniques that use one, and --view voxels | svo-steps):\n" + gi::optionHelp(gi::bindOptions(settings.voxels));
  u += "\nGI budget (every technique; docs/QUALITY.md, \"The GI budget\"):\n" + gi::optionHelp(gi::bindOptions(settings.budget));
  u += "\nWindowed: WASD move, hold the right mouse button to look, Q/E down/up, Esc quits.\n";
  return u;
}

std::string usageMarkdown() {
  const char* header = "| option | default | range | meaning |\n| --- | --- | --- | --- |\n";
  std::string md =
      "# dyngi_sample options\n\n"
      "Generated by `dyngi_sample --help-markdown` from the sample's flag table and the GI's option tables;\n"
      "`SampleCli.OptionsDocIsTheGeneratedOne` holds this file equal to that output.\n\n"
      "## The sample\n\n| option | default | meaning |\n| --- | --- | --- |\n";
  const Options defaults;
  for (const SampleFlag& f : sampleFlags())
    md += "| `" + markdownCell(sampleFlagColumn(f)) + "` | " + (f.shown ? f.shown(defaults) : "") + " | " + markdownCell(f.help) + " |\n";
  md += "\n`--gi`: " + joined(giModes(), ", ") + ". `--scene NAME`: " + joined(builtinSceneNames(), ", ") + ". `--animate`: " +
        joined(animatedSceneNames(), ", ") + ".\n";
  gi::GiSettings settings;
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    md += "\n## `--gi " + std::string(e.name) + "`\n\n" + e.summary + ".\n\nViews: `final`, `indirect`";
    for (const char* v : e.debugViews) md += std::string(", `") + v + "`";
    md += ".\n\n" + std::string(header) + gi::optionMarkdown(e.options(settings));
  }
  gi::PathTracerSettings pt;
  md += "\n## `--gi path`: the reference path tracer\n\n" + std::string(header) + gi::optionMarkdown(gi::bindOptions(pt));
  md += "\n## The voxel scene\n\nFor the techniques that use one, and `--view voxels|svo-steps` with any `--gi`.\n\n" + std::string(header) +
        gi::optionMarkdown(gi::bindOptions(settings.voxels));
  md += "\n## The GI budget\n\nEvery technique (docs/QUALITY.md, \"The GI budget\").\n\n" + std::string(header) +
        gi::optionMarkdown(gi::bindOptions(settings.budget));
  return md;
}

int Options::warmupFrames() const {
  if (warmup >= 0) return warmup;
  const int total = frames > 0 ? frames : (headless ? kHeadlessDefaultFrames : -1);
  return total > 0 ? std::min(2, total - 1) : 2;
}

std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error) {
  Options o;
  Deferred deferred;
  error = parseArguments(std::vector<std::string>(argv + 1, argv + argc), o, deferred);
  if (error.empty() && o.usesGiSystem()) o.giSettings.technique = o.gi;
  if (error.empty()) error = applyTableOptions(o, deferred);
  if (error.empty()) error = checkView(o);
  const int frames = o.frames > 0 ? o.frames : (o.headless ? kHeadlessDefaultFrames : -1);
  if (error.empty() && o.warmup >= 0 && frames > 0 && o.warmup >= frames)
    error = "--warmup " + std::to_string(o.warmup) + " leaves none of the run's " + std::to_string(frames) + " frames to time";
  if (!error.empty()) return std::nullopt;
  return o;
}

std::string checkOutputPaths(const Options& o) {
  namespace fs = std::filesystem;
  const std::pair<const char*, const std::string*> outputs[] = {
      {"--out", &o.out}, {"--hdr-out", &o.hdrOut}, {"--stats", &o.stats}, {"--memory-log", &o.memoryLog}};
  for (const auto& [flag, path] : outputs)
    if (!path->empty())
      if (std::string bad = platform::checkOutputPath(*path); !bad.empty()) return std::string(flag) + " " + bad;
  std::error_code ec;
  if (!o.recordDir.empty() && !fs::is_directory(o.recordDir, ec))
    return "--record " + platform::oneLine(o.recordDir) + ": not a directory (it is not created)";
  return {};
}

}  // namespace dyngi::sample
