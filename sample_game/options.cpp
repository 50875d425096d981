#include "options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <vector>

namespace dyngi::sample {

namespace {

const char* const kGiModes[] = {"off", "svo", "bvh", "vct", "path"};
const char* const kEngineViews[] = {"final", "voxels", "svo-steps"};  // the voxel scene's and the default

// The command line that selects each technique of the registry (a new technique adds its --gi here).
std::string flagsOf(std::string_view technique) {
  if (technique == "temporal") return "--gi svo | --gi bvh";
  if (technique == "many_lights") return "--gi svo --vpl-source rsm";
  if (technique == "vct") return "--gi vct";
  return "--gi " + std::string(technique);
}

// --gi and --vpl-source pick the technique (and the temporal technique's visibility).
void selectTechnique(Options& o) {
  if (!o.usesGiSystem()) return;
  if (o.gi == "vct") {
    o.giSettings.technique = "vct";
    return;
  }
  o.giSettings.technique = o.vplSource == "rsm" ? "many_lights" : "temporal";
  o.giSettings.temporal.visibility = o.gi == "bvh" ? gi::VisibilityBackend::Bvh : gi::VisibilityBackend::Svo;
}

bool parseUint(const std::string& s, uint32_t& out) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

void append(std::vector<gi::OptionRef>& to, std::vector<gi::OptionRef> from) { to.insert(to.end(), from.begin(), from.end()); }

// Every option this run can take: the technique's, the path tracer's (--gi path), the voxel scene's.
std::vector<gi::OptionRef> acceptedOptions(Options& o) {
  std::vector<gi::OptionRef> refs;
  if (o.usesGiSystem()) {
    if (const gi::TechniqueEntry* e = gi::findTechnique(o.giSettings.technique)) append(refs, e->options(o.giSettings));
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
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry())
    for (const gi::OptionRef& r : e.options(probe))
      if (name == r.spec->name) return flag + " is an option of " + flagsOf(e.name) + ", not of --gi " + o.gi + (o.gi == "svo" ? " --vpl-source " + o.vplSource : "");
  gi::PathTracerSettings pt;
  for (const gi::OptionRef& r : gi::bindOptions(pt))
    if (name == r.spec->name) return flag + " is an option of --gi path, not of --gi " + o.gi;
  for (const gi::OptionRef& r : gi::bindOptions(probe.budget))
    if (name == r.spec->name) return flag + " is an option of --gi svo | --gi bvh | --gi vct, not of --gi " + o.gi;
  return "unknown option '" + flag + "' (see --help)";
}

}  // namespace

std::string usage() {
  std::string u =
      "usage: dyngi_sample [options]\n"
      "  --scene PATH|NAME                      a .gltf/.glb file or a built-in scene: cornell, cornell-dynamic (default),\n"
      "                                         showcase (the main job's: an uplight, so mostly bounce light),\n"
      "                                         two-rooms, two-rooms-door (a thin wall between two rooms: the leak test)\n"
      "  --headless                             render offscreen, no window\n"
      "  --size WxH                             render size (default 768x768)\n"
      "  --frames N                             frames to render (default: 60 headless, until closed windowed)\n"
      "  --gi MODE                              global illumination: off | svo (VPLs, SVO visibility on the GPU) |\n"
      "                                         bvh (VPLs, Embree visibility on the CPU) | vct (voxel cone tracing) |\n"
      "                                         path (reference path tracer)\n"
      "  --vpl-source paths|rsm                 incremental light paths (default) or per-frame RSM sampling (svo)\n"
      "  --animate NAME                         static | moving-spot | rotating-object | moving-camera |\n"
      "                                         walking-fox | fox-and-spot | fox-spot-light-on (benchmark, soak and\n"
      "                                         GI budget scenes: the last switches a second spot on at 4 s)\n"
      "  --out FILE.png                         write the last frame (tone-mapped, sRGB)\n"
      "  --hdr-out FILE.exr                     write the last frame's linear radiance before exposure\n"
      "  --stats FILE.json                      write timings (medians over frames after warm-up) and the settings used\n"
      "  --memory-log FILE.tsv                  every 100 frames: frame, resident memory, live Vulkan allocations\n"
      "  --warmup N                             frames left out of the medians (default 2, fewer for shorter runs;\n"
      "                                         e.g. T + 2 to time the steady state once every temporal set is filled)\n"
      "  --stage-times timestamps|fenced        how --stats times each pass: GPU timestamps (default; on lavapipe they\n"
      "                                         miss compute work) or the CPU clock between fences at every pass'\n"
      "                                         ends (each pass' own cost; the frame loses the overlap between passes)\n"
      "  --view NAME                            final | voxels | svo-steps | a technique's debug view (below)\n"
      "  --clip NAME                            glTF animation clip to play (default: the first)\n"
      "  --ui on|off|auto                       the settings panel (default auto: in a window, not headless)\n"
      "  --input-script FILE                    replay clicks and keys from FILE (format: sample_game/play/input.h);\n"
      "                                         fixed time step, ends after its last event unless --frames\n"
      "  --record DIR                           write every frame's displayed image to DIR/frame_NNNNN.png\n"
      "  --exposure X                           linear exposure multiplier (default 1)\n"
      "  --validation                           enable Vulkan validation layers\n"
      "  --help                                 this text\n";
  gi::GiSettings defaults;
  for (const gi::TechniqueEntry& e : gi::techniqueRegistry()) {
    u += "\nTechnique " + std::string(e.name) + " (" + flagsOf(e.name) + "): " + e.summary + "\n";
    if (!e.debugViews.empty()) {
      u += "  views:";
      for (const char* v : e.debugViews) u += std::string(" ") + v;
      u += "\n";
    }
    u += gi::optionHelp(e.options(defaults));
  }
  gi::PathTracerSettings pt;
  u += "\nReference path tracer (--gi path):\n" + gi::optionHelp(gi::bindOptions(pt));
  u += "\nVoxel scene (--gi svo | vct, --view voxels | svo-steps):\n" + gi::optionHelp(gi::bindOptions(defaults.voxels));
  u += "\nGI budget (--gi svo | bvh | vct; docs/QUALITY.md, \"The GI budget\"):\n" + gi::optionHelp(gi::bindOptions(defaults.budget));
  u += "\nWindowed: WASD move, hold the right mouse button to look, Q/E down/up, Esc quits.\n";
  return u;
}

int Options::warmupFrames() const {
  if (warmup >= 0) return warmup;
  const int total = frames > 0 ? frames : (headless ? kHeadlessDefaultFrames : -1);
  return total > 0 ? std::min(2, total - 1) : 2;
}

std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  // Table options wait until --gi and --vpl-source are known: they say which tables apply.
  std::vector<std::pair<std::string, std::optional<std::string>>> deferred;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& v) {
      if (i + 1 >= args.size()) {
        error = a + " needs a value";
        return false;
      }
      v = args[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--headless") o.headless = true;
    else if (a == "--validation") o.validation = true;
    else if (a == "--scene") { if (!value(o.scene)) return std::nullopt; }
    else if (a == "--out") { if (!value(o.out)) return std::nullopt; }
    else if (a == "--hdr-out") { if (!value(o.hdrOut)) return std::nullopt; }
    else if (a == "--stats") { if (!value(o.stats)) return std::nullopt; }
    else if (a == "--memory-log") { if (!value(o.memoryLog)) return std::nullopt; }
    else if (a == "--clip") { if (!value(o.clip)) return std::nullopt; }
    else if (a == "--view") { if (!value(o.view)) return std::nullopt; }
    else if (a == "--input-script") { if (!value(o.inputScript)) return std::nullopt; }
    else if (a == "--record") { if (!value(o.recordDir)) return std::nullopt; }
    else if (a == "--stage-times") {
      if (!value(o.stageTimes)) return std::nullopt;
      if (o.stageTimes != "timestamps" && o.stageTimes != "fenced") {
        error = "--stage-times wants timestamps or fenced, got '" + o.stageTimes + "'";
        return std::nullopt;
      }
    }
    else if (a == "--ui") {
      if (!value(o.ui)) return std::nullopt;
      if (o.ui != "on" && o.ui != "off" && o.ui != "auto") {
        error = "--ui wants on, off or auto, got '" + o.ui + "'";
        return std::nullopt;
      }
    }
    else if (a == "--size") {
      if (!value(v)) return std::nullopt;
      auto x = v.find('x');
      if (x == std::string::npos || !parseUint(v.substr(0, x), o.width) || !parseUint(v.substr(x + 1), o.height) ||
          o.width == 0 || o.height == 0 || o.width > 8192 || o.height > 8192) {
        error = "--size wants WxH with 1..8192 each, got '" + v + "'";
        return std::nullopt;
      }
    } else if (a == "--frames") {
      uint32_t n;
      if (!value(v)) return std::nullopt;
      if (!parseUint(v, n) || n == 0 || n > 1000000) {
        error = "--frames wants a positive integer, got '" + v + "'";
        return std::nullopt;
      }
      o.frames = int(n);
    } else if (a == "--warmup") {
      if (!value(v)) return std::nullopt;
      uint32_t n;
      if (!parseUint(v, n) || n > 1000000) {
        error = "--warmup wants a frame count, got '" + v + "'";
        return std::nullopt;
      }
      o.warmup = int(n);
    } else if (a == "--vpl-source") {
      if (!value(o.vplSource)) return std::nullopt;
      if (o.vplSource != "paths" && o.vplSource != "rsm") {
        error = "unknown --vpl-source '" + o.vplSource + "' (available: paths, rsm)";
        return std::nullopt;
      }
    } else if (a == "--animate") {
      if (!value(o.animate)) return std::nullopt;
      if (o.animate != "static" && o.animate != "moving-spot" && o.animate != "rotating-object" && o.animate != "moving-camera" &&
          o.animate != "walking-fox" && o.animate != "fox-and-spot" && o.animate != "fox-spot-light-on") {
        error = "unknown --animate '" + o.animate +
                "' (available: static, moving-spot, rotating-object, moving-camera, walking-fox, fox-and-spot, fox-spot-light-on)";
        return std::nullopt;
      }
    } else if (a == "--exposure") {
      if (!value(v)) return std::nullopt;
      float f = 0;
      auto r = std::from_chars(v.data(), v.data() + v.size(), f);
      if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(f) || f <= 0) {
        error = "--exposure wants a positive number, got '" + v + "'";
        return std::nullopt;
      }
      o.exposure = f;
    } else if (a == "--gi") {
      if (!value(o.gi)) return std::nullopt;
      bool known = false;
      for (const char* m : kGiModes) known |= o.gi == m;
      if (!known) {
        error = "unknown --gi mode '" + o.gi + "' (available: off, svo, bvh, vct, path)";
        return std::nullopt;
      }
    } else if (a.rfind("--", 0) == 0 && a.size() > 2) {
      std::optional<std::string> next;
      if (i + 1 < args.size()) next = args[++i];
      deferred.emplace_back(a, next);
    } else {
      error = "unknown option '" + a + "' (see --help)";
      return std::nullopt;
    }
  }
  if (o.vplSource == "rsm" && o.gi == "bvh") {
    error = "--vpl-source rsm needs --gi svo";
    return std::nullopt;
  }
  selectTechnique(o);
  const std::vector<gi::OptionRef> accepted = acceptedOptions(o);
  for (const auto& [flag, text] : deferred) {
    const std::string name = flag.substr(2);  // a copy: clang 14 cannot capture a structured binding
    auto it = std::find_if(accepted.begin(), accepted.end(), [&](const gi::OptionRef& r) { return name == r.spec->name; });
    if (it == accepted.end()) {
      error = notForThisRun(o, flag);
      return std::nullopt;
    }
    if (!text) {
      error = flag + " needs a value";
      return std::nullopt;
    }
    error = gi::parseOptionValue(*it, *text);
    if (!error.empty()) return std::nullopt;
  }
  // --view: the voxel scene's views, or one of the technique's.
  bool knownView = std::find(std::begin(kEngineViews), std::end(kEngineViews), o.view) != std::end(kEngineViews);
  const gi::TechniqueEntry* active = o.usesGiSystem() ? gi::findTechnique(o.giSettings.technique) : nullptr;
  if (!knownView && active)
    for (const char* v : active->debugViews) knownView |= o.view == v;
  if (!knownView) {
    for (const gi::TechniqueEntry& e : gi::techniqueRegistry())
      for (const char* v : e.debugViews)
        if (o.view == v) {
          error = "--view " + o.view + " needs " + flagsOf(e.name) + " (a view of the " + e.name + " technique)";
          return std::nullopt;
        }
    error = "unknown --view '" + o.view + "' (see --help for each technique's views)";
    return std::nullopt;
  }
  const int frames = o.frames > 0 ? o.frames : (o.headless ? kHeadlessDefaultFrames : -1);
  if (o.warmup >= 0 && frames > 0 && o.warmup >= frames) {
    error = "--warmup " + std::to_string(o.warmup) + " leaves none of the run's " + std::to_string(frames) + " frames to time";
    return std::nullopt;
  }
  return o;
}

std::string checkOutputPaths(const Options& o) {
  namespace fs = std::filesystem;
  const std::pair<const char*, const std::string*> outputs[] = {
      {"--out", &o.out}, {"--hdr-out", &o.hdrOut}, {"--stats", &o.stats}, {"--memory-log", &o.memoryLog}};
  for (const auto& [flag, path] : outputs) {
    if (path->empty()) continue;
    std::error_code ec;
    fs::path p(*path);
    fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(dir, ec))
      return std::string(flag) + " " + *path + ": directory '" + dir.string() + "' does not exist (it is not created)";
    if (fs::is_directory(p, ec)) return std::string(flag) + " " + *path + ": is a directory, not a file";
  }
  std::error_code ec;
  if (!o.recordDir.empty() && !fs::is_directory(o.recordDir, ec))
    return "--record " + o.recordDir + ": not a directory (it is not created)";
  return {};
}

}  // namespace dyngi::sample
