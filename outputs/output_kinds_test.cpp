#include "output_kinds.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

// Frame i's timestamp is the decimal product i × interval, as the double nearest it: what a
// reader of the manifest, COCO or poses.tum expects, and what EuRoC's names say in ns.
TEST(FrameTimestamps, AreTheIntervalsDecimalMultiples) {
  EXPECT_EQ(frameTimestampSeconds(3, 0.1), 0.3);  // 3 · 0.1 in doubles is 0.30000000000000004
  EXPECT_EQ(frameTimestampSeconds(3, 33.3), 99.9);  // an interval of 16 s or more (99.89999999999999)
  EXPECT_EQ(frameTimestampSeconds(60935, 48947.189), 2982596961.715);  // beyond 2^53 ns: rounded once
  EXPECT_EQ(frameTimestampSeconds(0, 0.1), 0.0);
  EXPECT_EQ(frameTimestampNs(3, 33.3), 99900000000);
  EXPECT_EQ(frameTimestampNs(99999, 65537.953), int64_t{99999} * 65537953000000);
  EXPECT_EQ(frameTimestampNs(100000, 86400.0), int64_t{100000} * 86400000000000);  // the largest
  // An interval of no whole number of ns is multiplied as it is.
  EXPECT_EQ(frameTimestampNs(7, 1.0 / 30.0), 233333333);
  EXPECT_EQ(eurocImageName(3, 0.05), "150000000.png");
}

}  // namespace
}  // namespace omnicam
