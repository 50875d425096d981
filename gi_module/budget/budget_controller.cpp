#include "dyngi/gi/budget_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dyngi::gi {

namespace {
// A level's cost this much below what it cost when an up-step from it failed: the load fell, try again.
constexpr double kLoadDrop = 0.15;
}  // namespace

const OptionTable<BudgetOptions>& BudgetOptions::table() {
  static const OptionTable<BudgetOptions> t = OptionTable<BudgetOptions>("gi").add(
      DYNGI_OPTION(BudgetOptions, budgetMs), "hold the GI's milliseconds per frame near this by lowering the technique's quality knobs (0: off)", 0, 10000);
  return t;
}

std::vector<double> geometricLevels(double full, double floorFraction, double ratio, double multiple) {
  std::vector<double> levels;
  if (!(full > 0.0) || !(ratio > 0.0 && ratio < 1.0) || !(multiple > 0.0)) return {full};
  const double floorValue = std::max(multiple, full * floorFraction);
  for (double x = full;; x *= ratio) {
    double q = std::max(multiple, std::floor(x / multiple + 1e-9) * multiple);
    if (!levels.empty() && q < floorValue) q = std::max(multiple, std::floor(floorValue / multiple + 1e-9) * multiple);
    if (levels.empty() || q < levels.back()) levels.push_back(q);
    if (q <= floorValue || levels.size() > 64) break;
  }
  return levels;
}

BudgetController::BudgetController(double budgetMs, std::vector<QualityKnob> knobs, const BudgetControllerSettings& settings)
    : budget_(budgetMs), knobs_(std::move(knobs)), settings_(settings) {
  if (!(budget_ > 0.0)) throw std::invalid_argument("a GI budget must be positive");
  settings_.window = std::max(1u, settings_.window);
  std::vector<uint32_t> at(knobs_.size(), 0);
  ladder_.push_back(at);
  for (size_t k = 0; k < knobs_.size(); ++k)
    for (size_t j = 1; j < knobs_[k].levels.size(); ++j) {
      at[k] = uint32_t(j);
      ladder_.push_back(at);
    }
  logStepRatio_.assign(ladder_.size() - 1, std::log(settings_.assumedStepRatio));
  stepLearned_.assign(ladder_.size() - 1, false);
}

std::vector<std::pair<std::string, double>> BudgetController::valuesAt(uint32_t level) const {
  std::vector<std::pair<std::string, double>> v;
  for (size_t k = 0; k < knobs_.size(); ++k)
    if (!knobs_[k].levels.empty()) v.emplace_back(knobs_[k].name, knobs_[k].levels[ladder_[level][k]]);
  return v;
}

double BudgetController::predicted(double medianMs, uint32_t from, uint32_t to) const {
  double sum = 0.0;
  for (uint32_t i = std::min(from, to); i < std::max(from, to); ++i) sum += logStepRatio_[i];
  return medianMs * std::exp(to > from ? sum : -sum);
}

void BudgetController::learn(uint32_t from, uint32_t to, double before, double after) {
  if (from == to || !(before > 0.0) || !(after > 0.0)) return;
  // The cost ratio of the whole move, spread evenly over its steps. A step never makes the GI dearer:
  // a measured ratio above 1 is noise.
  const uint32_t lo = std::min(from, to), hi = std::max(from, to);
  const double cheaperOverDearer = to > from ? after / before : before / after;
  const double perStep = std::min(0.0, std::log(cheaperOverDearer) / double(hi - lo));
  for (uint32_t i = lo; i < hi; ++i) {
    logStepRatio_[i] = stepLearned_[i] ? 0.5 * (logStepRatio_[i] + perStep) : perStep;
    stepLearned_[i] = true;
  }
}

void BudgetController::moveTo(uint32_t level, double medianMs) {
  const bool up = level < level_;
  if (!up && lastMoveUp_ && sinceChange_.size() <= 3 * settings_.window) {
    // Down soon after up: that up-step did not fit. Wait before trying it again, longer each time.
    backoff_ = backoff_ ? std::min(2 * backoff_, settings_.maxBackoffFrames) : settings_.backoffFrames;
    upBlockedUntil_ = measured_.size() + backoff_;
    blockedAtMs_ = lastMedian_;  // the cost here before that up-step: the block lifts if the load falls well below it
  }
  lastFrom_ = level_;
  lastMedian_ = medianMs;
  pendingLearn_ = true;
  lastMoveUp_ = up;
  level_ = level;
  sinceChange_.clear();
  changes_.push_back({measured_.size(), level_, medianMs});
  const std::vector<uint32_t>& at = ladder_[level_];
  for (size_t k = 0; k < knobs_.size(); ++k)
    if (knobs_[k].apply && !knobs_[k].levels.empty()) knobs_[k].apply(knobs_[k].levels[at[k]]);
}

void BudgetController::setBudgetMs(double budgetMs) {
  if (!(budgetMs > 0.0)) throw std::invalid_argument("a GI budget must be positive");
  budget_ = budgetMs;
  sinceChange_.clear();
  backoff_ = 0;
  upBlockedUntil_ = 0;
  blockedAtMs_ = 0.0;
  met_ = true;
}

bool BudgetController::onFrame(double giMs) {
  if (!std::isfinite(giMs) || giMs < 0.0) return false;  // a frame that could not be timed
  measured_.push_back(giMs);
  sinceChange_.push_back(giMs);
  // Far over the budget before any decision: decide on the first few frames.
  const bool farOverAtStart = changes_.empty() && sinceChange_.size() >= settings_.firstWindow &&
                              std::all_of(sinceChange_.begin(), sinceChange_.end(), [&](double ms) { return ms > 2.0 * budget_; });
  if (sinceChange_.size() < settings_.window && !farOverAtStart) return false;
  const size_t n = std::min<size_t>(sinceChange_.size(), settings_.window);
  std::vector<double> last(sinceChange_.end() - n, sinceChange_.end());
  std::nth_element(last.begin(), last.begin() + last.size() / 2, last.end());
  const double median = last[last.size() / 2];
  if (pendingLearn_) {
    learn(lastFrom_, level_, lastMedian_, median);
    pendingLearn_ = false;
  }
  // A level that held long enough forgets earlier failures.
  if (!changes_.empty() && measured_.size() - changes_.back().frame > settings_.maxBackoffFrames) backoff_ = 0;

  if (median > budget_ * (1.0 + settings_.overTolerance)) {
    if (level_ == floorLevel()) {
      met_ = false;
      return false;
    }
    uint32_t target = level_ + 1;
    while (target < floorLevel() && predicted(median, level_, target) > budget_) ++target;
    moveTo(target, median);
    return true;
  }
  met_ = true;
  const bool upAllowed = measured_.size() >= upBlockedUntil_ || median < blockedAtMs_ * (1.0 - kLoadDrop);
  if (level_ > 0 && median <= budget_ && upAllowed && predicted(median, level_, level_ - 1) <= budget_) {
    moveTo(level_ - 1, median);
    return true;
  }
  return false;
}

}  // namespace dyngi::gi
