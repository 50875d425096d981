#include "dyngi/engine/ecs/scheduler.h"

#include <algorithm>
#include <chrono>
#include <limits>

namespace dyngi::ecs {

const char* phaseName(Phase p) {
  switch (p) {
    case Phase::Update: return "update";
    case Phase::PostUpdate: return "post_update";
    case Phase::Extract: return "extract";
    case Phase::Render: return "render";
    default: return "?";
  }
}

namespace {
class LambdaSystem final : public System {
 public:
  LambdaSystem(std::string name, std::function<void(World&, const SystemContext&)> fn)
      : name_(std::move(name)), fn_(std::move(fn)) {}
  const char* name() const override { return name_.c_str(); }
  void run(World& w, const SystemContext& c) override { fn_(w, c); }

 private:
  std::string name_;
  std::function<void(World&, const SystemContext&)> fn_;
};
}  // namespace

System& Scheduler::add(Phase phase, std::unique_ptr<System> system) {
  auto& list = phases_[size_t(phase)];
  list.push_back({std::move(system), 0});
  return *list.back().system;
}

System& Scheduler::add(Phase phase, std::string name, std::function<void(World&, const SystemContext&)> fn) {
  return add(phase, std::make_unique<LambdaSystem>(std::move(name), std::move(fn)));
}

void Scheduler::runFrame(World& world, const FrameTime& time) {
  timings_.clear();
  Tick oldest = std::numeric_limits<Tick>::max();
  for (auto& phase : phases_) {
    for (auto& entry : phase) {
      auto t0 = std::chrono::steady_clock::now();
      entry.system->run(world, SystemContext{entry.lastRun, time});
      world.flushCommands();
      auto t1 = std::chrono::steady_clock::now();
      entry.lastRun = world.tick();
      // Whatever is written next (the next system, or the host between frames) gets a newer tick.
      world.advanceTick();
      oldest = std::min(oldest, entry.lastRun);
      timings_.push_back({entry.system->name(), std::chrono::duration<double, std::milli>(t1 - t0).count()});
    }
  }
  // Every system has seen everything up to its own last run; records older than the oldest of those
  // are no longer needed. (Callers that query with older ticks fall back to a scan, still correct.)
  if (oldest != std::numeric_limits<Tick>::max()) world.trimChangeLogs(oldest);
}

}  // namespace dyngi::ecs
