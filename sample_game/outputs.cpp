#include "outputs.h"

#include <sys/resource.h>
#include <unistd.h>

#include "dyngi/engine/platform/files.h"
#include "dyngi/engine/render/image_io.h"

namespace dyngi::sample {

namespace {
// Resident set size of this process, from /proc (0 where there is none).
uint64_t residentKiB() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long sizePages = 0, residentPages = 0;
  int n = std::fscanf(f, "%llu %llu", &sizePages, &residentPages);
  std::fclose(f);
  return n == 2 ? residentPages * uint64_t(sysconf(_SC_PAGESIZE)) / 1024 : 0;
}

int report(const std::string& err, const std::string& path) {
  if (!err.empty()) {
    std::fprintf(stderr, "dyngi_sample: %s\n", platform::oneLine(err, 1000).c_str());
    return 1;
  }
  std::printf("wrote %s\n", path.c_str());
  return 0;
}
}  // namespace

int writeImages(const Options& o, uint32_t width, uint32_t height, const std::function<std::vector<uint8_t>()>& ldr,
                const std::function<render::ImageRgba()>& hdr) {
  int status = 0;
  if (!o.out.empty()) status |= report(render::writePng(o.out, width, height, ldr()), o.out);
  if (!o.hdrOut.empty()) status |= report(render::writeExr(o.hdrOut, width, height, hdr()), o.hdrOut);
  return status;
}

int writeStats(const Options& o, const RunStats& stats) {
  int status = 0;
  if (!o.stats.empty()) {
    const std::string json = stats.toJson();
    status |= report(platform::writeOutputFile(o.stats, json.data(), json.size()), o.stats);
  }
  std::printf("%s", stats.table().c_str());
  return status;
}

bool MemoryLog::open(const std::string& path) {
  if (path.empty()) return true;
  path_ = path;
  if (std::string err = file_.open(path); !err.empty()) {
    std::fprintf(stderr, "dyngi_sample: %s\n", platform::oneLine(err, 1000).c_str());
    return false;
  }
  file_.write("frame\trss_kib\tvk_allocations\tvk_device_bytes\n");
  return true;
}

int MemoryLog::close() {
  if (!file_.isOpen()) return 0;
  return report(file_.close(), path_);
}

void MemoryLog::frameRendered(int rendered, const render::VulkanContext& ctx) {
  if (!file_.isOpen() || rendered % kEvery != 0) return;
  const uint64_t deviceBytes = ctx.deviceBytesInUse();
  char line[128];
  std::snprintf(line, sizeof line, "%d\t%llu\t%llu\t%llu\n", rendered, (unsigned long long)residentKiB(), (unsigned long long)ctx.liveAllocations(),
                (unsigned long long)deviceBytes);
  file_.write(line);
}

void addMemory(RunStats& stats, const render::VulkanContext& ctx) {
  constexpr double kMiB = 1024.0 * 1024.0;
  auto& m = stats.sections["memory"];
  m["device_mb"] = double(ctx.deviceBytesInUse()) / kMiB;
  m["device_peak_mb"] = double(ctx.deviceBytesPeak()) / kMiB;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) m["resident_peak_mb"] = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
}

void addSettings(RunStats& stats, const std::vector<gi::OptionRef>& options) {
  for (const gi::OptionRef& r : options) {
    if (r.isChoice()) stats.namedSettings[r.spec->name] = r.text();
    else stats.sections["settings"][r.spec->name] = r.get();
  }
}

}  // namespace dyngi::sample
