#pragma once
// A frame budget for the playable sample: the whole frame held near a target by giving the GI's budget
// (GiSystem::setBudgetMs) what the rest of the frame leaves. The first timed frame gives a first guess;
// then every kWindow timed frames the GI budget becomes the target minus the median of the rest
// (frame - GI) over them, at least kMinGiMs; a change under kHold of the current budget is left to the
// GI's own controller.
#include <cstdint>
#include <vector>

namespace dyngi::sample {

class FrameBudget {
 public:
  static constexpr uint32_t kWindow = 30;
  static constexpr double kMinGiMs = 1.0;
  static constexpr double kHold = 0.1;

  explicit FrameBudget(double targetMs = 0.0) : target_(targetMs) {}
  // 0: off (the GI keeps the budget it has).
  void setTarget(double ms);
  double target() const { return target_; }
  // The GI budget it last asked for (0 before the first window).
  double giBudget() const { return giBudget_; }
  // A rendered frame: its wall-clock milliseconds and the GI's (GiStats::giMs; below 0 when the frame
  // was not timed, and then left out). Returns the GI budget to set now, or 0 when it stays.
  double onFrame(double frameMs, double giMs);

 private:
  double target_;
  double giBudget_ = 0.0;
  std::vector<double> rest_;  // frame - GI, this window
};

}  // namespace dyngi::sample
