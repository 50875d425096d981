#include "options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <vector>

namespace dyngi::sample {

const char* const kGiModes[] = {"off", "svo", "bvh", "path"};

std::string usage() {
  return "usage: dyngi_sample [options]\n"
         "  --scene PATH|cornell|cornell-dynamic   scene to render (default cornell-dynamic)\n"
         "  --headless                             render offscreen, no window\n"
         "  --size WxH                             render size (default 768x768)\n"
         "  --frames N                             frames to render (default: 60 headless, until closed windowed)\n"
         "  --gi MODE                              global illumination: off | svo (VPLs, SVO visibility on the GPU) |\n"
         "                                         bvh (VPLs, Embree visibility on the CPU) | path (reference path tracer)\n"
         "  --temporal T                           temporal VPL sets for svo/bvh (default 16; 1 = all VPLs every frame)\n"
         "  --reshoot N                            VPLs reshot per frame (default: VPLs / T)\n"
         "  --vpl-source paths|rsm                 incremental light paths (default) or per-frame RSM sampling (svo)\n"
         "  --animate NAME                         static | moving-spot | rotating-object | moving-camera |\n"
         "                                         walking-fox | fox-and-spot (benchmark and soak scenes)\n"
         "  --vpls N                               VPLs for --gi svo (default 512)\n"
         "  --interleave K                         K x K interleaved sub-images (default 4)\n"
         "  --clamp B                              distance clamp B in world units^2 (default 0.01)\n"
         "  --spp N                                path tracer samples per pixel (default 64)\n"
         "  --bounces B                            indirect bounces: 0 = direct only, 1 = one bounce (default 1)\n"
         "  --out FILE.png                         write the last frame (tone-mapped, sRGB)\n"
         "  --hdr-out FILE.exr                     write the last frame's linear radiance before exposure\n"
         "  --stats FILE.json                      write timings (medians over frames after warm-up)\n"
         "  --memory-log FILE.tsv                  every 100 frames: frame, resident memory, live Vulkan allocations\n"
         "  --warmup N                             frames left out of the medians (default 2, fewer for shorter runs;\n"
         "                                         e.g. T + 2 to time the steady state once every temporal set is filled)\n"
         "  --view NAME                            final | voxels | svo-steps | indirect | vpls | subimages\n"
         "  --voxel-res N                          voxel resolution, a power of two in 64..512 (default 128)\n"
         "  --clip NAME                            glTF animation clip to play (default: the first)\n"
         "  --seed N                               seed of the path tracer's and the VPLs' random numbers (default 1)\n"
         "  --exposure X                           linear exposure multiplier (default 1)\n"
         "  --validation                           enable Vulkan validation layers\n"
         "  --help                                 this text\n"
         "Windowed: WASD move, hold the right mouse button to look, Q/E down/up, Esc quits.\n";
}

int Options::warmupFrames() const {
  if (warmup >= 0) return warmup;
  const int total = frames > 0 ? frames : (headless ? kHeadlessDefaultFrames : -1);
  return total > 0 ? std::min(2, total - 1) : 2;
}

namespace {
bool parseUint(const std::string& s, uint32_t& out) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}
}  // namespace

std::optional<Options> parseOptions(int argc, const char* const* argv, std::string& error) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
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
    else if (a == "--view") {
      if (!value(o.view)) return std::nullopt;
      const char* views[] = {"final", "voxels", "svo-steps", "indirect", "vpls", "subimages"};
      bool known = false;
      for (const char* name : views) known |= o.view == name;
      if (!known) {
        error = "unknown --view '" + o.view + "' (available: final, voxels, svo-steps, indirect, vpls, subimages)";
        return std::nullopt;
      }
    } else if (a == "--voxel-res") {
      if (!value(v)) return std::nullopt;
      if (!parseUint(v, o.voxelResolution) || o.voxelResolution < 64 || o.voxelResolution > 512 ||
          (o.voxelResolution & (o.voxelResolution - 1)) != 0) {
        error = "--voxel-res wants a power of two in 64..512, got '" + v + "'";
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
    } else if (a == "--seed") {
      if (!value(v)) return std::nullopt;
      if (!parseUint(v, o.seed)) {
        error = "--seed wants a non-negative integer, got '" + v + "'";
        return std::nullopt;
      }
    } else if (a == "--temporal" || a == "--reshoot") {
      uint32_t n;
      if (!value(v)) return std::nullopt;
      bool isT = a == "--temporal";
      if (!parseUint(v, n) || (isT ? (n < 1 || n > 32) : n > 1000000)) {
        error = a + (isT ? " wants 1..32" : " wants 0..1000000") + ", got '" + v + "'";
        return std::nullopt;
      }
      (isT ? o.temporal : o.reshoot) = n;
    } else if (a == "--vpl-source") {
      if (!value(o.vplSource)) return std::nullopt;
      if (o.vplSource != "paths" && o.vplSource != "rsm") {
        error = "unknown --vpl-source '" + o.vplSource + "' (available: paths, rsm)";
        return std::nullopt;
      }
    } else if (a == "--animate") {
      if (!value(o.animate)) return std::nullopt;
      if (o.animate != "static" && o.animate != "moving-spot" && o.animate != "rotating-object" && o.animate != "moving-camera" &&
          o.animate != "walking-fox" && o.animate != "fox-and-spot") {
        error = "unknown --animate '" + o.animate +
                "' (available: static, moving-spot, rotating-object, moving-camera, walking-fox, fox-and-spot)";
        return std::nullopt;
      }
    } else if (a == "--vpls" || a == "--interleave") {
      uint32_t n;
      if (!value(v)) return std::nullopt;
      bool isVpls = a == "--vpls";
      if (!parseUint(v, n) || (isVpls ? (n < 16 || n > 65536) : (n < 1 || n > 8))) {
        error = a + (isVpls ? " wants 16..65536" : " wants 1..8") + ", got '" + v + "'";
        return std::nullopt;
      }
      (isVpls ? o.vpls : o.interleave) = n;
    } else if (a == "--clamp") {
      if (!value(v)) return std::nullopt;
      float f = 0;
      auto r = std::from_chars(v.data(), v.data() + v.size(), f);
      if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(f) || f < 0) {
        error = "--clamp wants a number >= 0, got '" + v + "'";
        return std::nullopt;
      }
      o.distanceClamp = f;
    } else if (a == "--spp" || a == "--bounces") {
      uint32_t n;
      if (!value(v)) return std::nullopt;
      bool isSpp = a == "--spp";
      if (!parseUint(v, n) || (isSpp && (n == 0 || n > 1000000)) || (!isSpp && n > 64)) {
        error = a + (isSpp ? " wants 1..1000000" : " wants 0..64") + ", got '" + v + "'";
        return std::nullopt;
      }
      (isSpp ? o.spp : o.bounces) = n;
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
        error = "unknown --gi mode '" + o.gi + "' (available: off, svo, bvh, path)";
        return std::nullopt;
      }
    } else {
      error = "unknown option '" + a + "' (see --help)";
      return std::nullopt;
    }
  }
  // Combinations, checked here so bad input is refused before any device is created.
  const bool manyLightsView = o.view == "indirect" || o.view == "vpls" || o.view == "subimages";
  if (o.vplSource == "rsm" && o.gi == "bvh") {
    error = "--vpl-source rsm needs --gi svo";
    return std::nullopt;
  }
  if (manyLightsView && !(o.gi == "svo" && o.vplSource == "rsm")) {
    error = "--view " + o.view + " needs --gi svo --vpl-source rsm";
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
  return {};
}

}  // namespace dyngi::sample
