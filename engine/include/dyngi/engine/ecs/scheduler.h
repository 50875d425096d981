#pragma once
// Systems run in fixed phases, in registration order within a phase. Each system remembers the tick
// of its last run and asks the world what changed after it. The scheduler advances the world tick
// after every system (so the next writer, or the host between frames, writes at a newer tick),
// flushes deferred commands after each system, and times each on the CPU.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dyngi/engine/ecs/world.h"

namespace dyngi::ecs {

enum class Phase { Update, PostUpdate, Extract, Render, Count };
const char* phaseName(Phase p);

struct FrameTime {
  double dt = 1.0 / 60.0;  // seconds since last frame (fixed in headless runs, for reproducibility)
  double time = 0.0;       // seconds since start
  uint64_t frame = 0;
};

struct SystemContext {
  Tick lastRun = 0;  // the world tick at the end of this system's previous run (0: never ran)
  FrameTime time;
};

class System {
 public:
  virtual ~System() = default;
  virtual const char* name() const = 0;
  virtual void run(World& world, const SystemContext& ctx) = 0;
};

class Scheduler {
 public:
  System& add(Phase phase, std::unique_ptr<System> system);
  // Convenience for small systems written as a lambda.
  System& add(Phase phase, std::string name, std::function<void(World&, const SystemContext&)> fn);

  void runFrame(World& world, const FrameTime& time);

  struct Timing {
    std::string name;
    double cpuMs = 0;
  };
  const std::vector<Timing>& lastTimings() const { return timings_; }

 private:
  struct Entry {
    std::unique_ptr<System> system;
    Tick lastRun = 0;
  };
  std::array<std::vector<Entry>, size_t(Phase::Count)> phases_;
  std::vector<Timing> timings_;
};

}  // namespace dyngi::ecs
