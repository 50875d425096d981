#pragma once
// A closed-loop controller that holds the GI's cost per frame near a budget in milliseconds by moving
// the technique's own quality knobs (Technique::qualityKnobs).
//
// The knobs form one ladder of quality levels: level 0 is the user's settings, each step lowers the
// first knob that has not reached its floor, in the order the technique lists them (the knob whose loss
// shows least comes first), and the last level is every knob at its floor. Once every `window` frames
// the controller compares the median measured cost with the budget:
//   - above budget x (1 + overTolerance): it jumps to the first cheaper level predicted to fit;
//   - below the budget: it steps up one level when that level is predicted to fit the budget.
// Predictions use the cost ratio of each ladder step, learned from the medians measured on either side
// of the step (load-independent: a second light scales both sides), and `assumedStepRatio` until a
// step has been tried. An up-step that did not fit is not tried again for a back-off time that doubles
// each time (hysteresis: no limit cycle between two levels). At the floor and still over, it reports the
// budget as not met instead of degrading further.
//
// It reads nothing but the costs it is fed, so a test drives it with a synthetic cost model (an
// injected clock); GiSystem feeds it the GI's measured milliseconds (gi_system.h, GiStats::giMs).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dyngi/gi/options.h"

namespace dyngi::gi {

// One knob a technique lets the controller move.
struct QualityKnob {
  std::string name;            // as the stats name it, e.g. "vpls_per_frame"
  std::vector<double> levels;  // its values from the user's setting (index 0) down to its floor
  std::function<void(double)> apply;  // sets a value; the technique uses it from the next frame on
};

// The knob values `levels` from `full` down to `full x floorFraction`, each step x `ratio`, rounded
// down to a multiple of `multiple`, duplicates dropped: the ladder of a count-like knob whose cost is
// proportional to it (VPLs gathered).
std::vector<double> geometricLevels(double full, double floorFraction, double ratio, double multiple = 1.0);
// The techniques' count-like knobs go from the user's value down to an eighth of it, in steps of
// about 15 percent: fine enough that some level lands within the band the controller holds (a
// coarser step would leave the cost far under the budget), and an eighth keeps the image recognisable.
constexpr double kBudgetFloorFraction = 1.0 / 8.0;
constexpr double kBudgetStepRatio = 0.85;

// What a host sets: the budget (GiSettings::budget, --gi-budget-ms).
struct BudgetOptions {
  float budgetMs = 0.0f;  // the GI's milliseconds per frame to hold; 0: off (the technique's settings as given)
  static const OptionTable<BudgetOptions>& table();
};

struct BudgetControllerSettings {
  uint32_t window = 9;             // frames per decision (their median is the measured cost)
  // The first decision's frames when they all cost over twice the budget: a start far over it (a
  // window's default quality at 768^2) is left after a few frames, not a whole window of them.
  uint32_t firstWindow = 3;
  double overTolerance = 0.1;      // lower the quality above budget x (1 + this)
  double assumedStepRatio = 0.85;  // cost ratio of a ladder step not measured yet
  uint32_t backoffFrames = 30;     // a failed up-step waits this long, doubled at each failure
  uint32_t maxBackoffFrames = 960;
};

class BudgetController {
 public:
  BudgetController(double budgetMs, std::vector<QualityKnob> knobs, const BudgetControllerSettings& settings = {});

  // One frame's measured GI cost, recorded with the knobs as they were for that frame. Returns true
  // when it moved a knob (applied at once through the knob's apply()).
  bool onFrame(double giMs);

  double budgetMs() const { return budget_; }
  // A new budget from the next frame on (a frame budget that moves the GI's share): the level stays,
  // the next decision waits for a whole window, and earlier failures are forgotten.
  void setBudgetMs(double budgetMs);
  uint32_t level() const { return level_; }
  uint32_t floorLevel() const { return uint32_t(ladder_.size()) - 1; }
  // False while the controller sits at the floor and the cost is still above the budget.
  bool budgetMet() const { return met_; }
  // Each knob's value at the current level.
  std::vector<std::pair<std::string, double>> knobValues() const { return valuesAt(level_); }

  // The run so far: every measured cost, and each change of level (frame, level, cost median that led to it).
  struct Change {
    uint64_t frame;
    uint32_t level;
    double medianMs;
  };
  const std::vector<double>& measured() const { return measured_; }
  const std::vector<Change>& changes() const { return changes_; }
  const std::vector<QualityKnob>& knobs() const { return knobs_; }
  std::vector<std::pair<std::string, double>> valuesAt(uint32_t level) const;

 private:
  double predicted(double medianMs, uint32_t from, uint32_t to) const;
  void moveTo(uint32_t level, double medianMs);
  void learn(uint32_t from, uint32_t to, double before, double after);

  double budget_;
  std::vector<QualityKnob> knobs_;
  BudgetControllerSettings settings_;
  std::vector<std::vector<uint32_t>> ladder_;  // per level: each knob's index into its levels
  std::vector<double> logStepRatio_;           // per step (level i -> i + 1): log(cost ratio), learned
  std::vector<bool> stepLearned_;
  uint32_t level_ = 0;
  bool met_ = true;
  std::vector<double> measured_;
  std::vector<double> sinceChange_;            // costs measured at the current level
  std::vector<Change> changes_;
  // The last move: where from, and the median before it (to learn the step's ratio from the next window).
  uint32_t lastFrom_ = 0;
  double lastMedian_ = 0;
  bool pendingLearn_ = false;
  bool lastMoveUp_ = false;
  uint64_t upBlockedUntil_ = 0;  // frame before which the up-step that failed is not tried again...
  double blockedAtMs_ = 0;       // ... unless the cost here falls well below this (the load dropped)
  uint32_t backoff_ = 0;
};

}  // namespace dyngi::gi
