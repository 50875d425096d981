#include "play/frame_budget.h"

#include <algorithm>
#include <cmath>

namespace dyngi::sample {

void FrameBudget::setTarget(double ms) {
  target_ = std::isfinite(ms) ? std::max(0.0, ms) : 0.0;
  rest_.clear();
  giBudget_ = 0.0;  // the next window sets it afresh
}

double FrameBudget::onFrame(double frameMs, double giMs) {
  if (!(target_ > 0.0) || !std::isfinite(frameMs) || !std::isfinite(giMs) || giMs < 0.0) return 0.0;
  rest_.push_back(std::max(0.0, frameMs - giMs));
  if (giBudget_ == 0.0) {  // the first timed frame: a first guess, so the GI is budgeted from the start
    giBudget_ = std::max(kMinGiMs, target_ - rest_.back());
    rest_.clear();
    return giBudget_;
  }
  if (rest_.size() < kWindow) return 0.0;
  std::nth_element(rest_.begin(), rest_.begin() + rest_.size() / 2, rest_.end());
  const double rest = rest_[rest_.size() / 2];
  rest_.clear();
  const double budget = std::max(kMinGiMs, target_ - rest);
  if (giBudget_ > 0.0 && std::abs(budget - giBudget_) <= kHold * giBudget_) return 0.0;
  giBudget_ = budget;
  return budget;
}

}  // namespace dyngi::sample
