// The sample's run statistics: medians as documented, and nothing timed reads as null, not as zero.
#include <gtest/gtest.h>

#include <cmath>

#include "stats.h"

using dyngi::sample::percentile;
using dyngi::sample::RunStats;

TEST(RunStats, MedianIsTheMiddleValueOrTheMeanOfTheMiddlePair) {
  EXPECT_DOUBLE_EQ(percentile({5, 1, 3}, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.95), 10.0);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

TEST(RunStats, NoTimedFrameIsNullNotZero) {
  RunStats s;
  s.frames = 2;
  s.warmupFrames = 2;
  std::string j = s.toJson();
  EXPECT_NE(j.find("\"frame_ms\": {\"median\": null, \"p95\": null}"), std::string::npos) << j;
  EXPECT_NE(s.table().find("no frame timed"), std::string::npos);
  s.frameMs = {10.0, 30.0, 20.0};
  EXPECT_NE(s.toJson().find("\"median\": 20.0000"), std::string::npos);
}
