// The sample's frame budget (sample_game/play/frame_budget.h) on synthetic frames: the GI budget it asks
// for is the target minus the median of the rest of the frame, held while it moves little.
#include <gtest/gtest.h>

#include <cmath>

#include "play/frame_budget.h"

using dyngi::sample::FrameBudget;

TEST(FrameBudget, TheGiGetsWhatTheRestOfTheFrameLeaves) {
  FrameBudget off;
  EXPECT_EQ(off.onFrame(500.0, 400.0), 0.0) << "off: the GI keeps its budget";

  FrameBudget b(100.0);
  EXPECT_EQ(b.onFrame(80.0, -1.0), 0.0) << "an untimed frame says nothing";
  EXPECT_DOUBLE_EQ(b.onFrame(90.0, 30.0), 40.0) << "the first timed frame: a first guess (100 - 60)";
  // A window of frames whose rest is 50 ms, five of them with a 500 ms hitch: the median leaves those out.
  double set = 0.0;
  for (uint32_t i = 0; i < FrameBudget::kWindow; ++i) set = b.onFrame(i % 6 == 0 ? 530.0 : 80.0, 30.0);
  EXPECT_DOUBLE_EQ(set, 50.0);
  EXPECT_DOUBLE_EQ(b.giBudget(), 50.0);
  // The rest grows by 2 ms: within kHold of the budget, the GI's own controller keeps holding it.
  for (uint32_t i = 0; i < FrameBudget::kWindow; ++i) set = b.onFrame(82.0, 30.0);
  EXPECT_EQ(set, 0.0);
  // The rest grows to 80 ms: the GI gets 20.
  for (uint32_t i = 0; i < FrameBudget::kWindow; ++i) set = b.onFrame(100.0, 20.0);
  EXPECT_DOUBLE_EQ(set, 20.0);
  // Nothing left for the GI: the floor, not zero or negative.
  for (uint32_t i = 0; i < FrameBudget::kWindow; ++i) set = b.onFrame(140.0, 20.0);
  EXPECT_DOUBLE_EQ(set, FrameBudget::kMinGiMs);
  // A new target starts afresh; NaN is off.
  b.setTarget(200.0);
  EXPECT_DOUBLE_EQ(b.onFrame(150.0, 50.0), 100.0);
  b.setTarget(std::nan(""));
  EXPECT_EQ(b.target(), 0.0);
  EXPECT_EQ(b.onFrame(150.0, 50.0), 0.0);
}
