#include "statistics.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

TEST(Statistics, MeanAndMedianOfSmallSamples) {
  EXPECT_FALSE(meanOf({}).has_value());
  EXPECT_FALSE(medianOf({}).has_value());
  EXPECT_DOUBLE_EQ(*meanOf({1.0, 2.0, 6.0}), 3.0);
  EXPECT_DOUBLE_EQ(*medianOf({6.0, 1.0, 2.0}), 2.0);               // odd: the middle value
  EXPECT_DOUBLE_EQ(*medianOf({9.0, 1.0, 4.0, 2.0}), 3.0);          // even: the mean of 2 and 4
  EXPECT_DOUBLE_EQ(*medianOf({5.0, 5.0, 1.0, 1000.0, 3.0}), 5.0);  // a far outlier moves the mean, not the median
  EXPECT_DOUBLE_EQ(*meanOf({5.0, 5.0, 1.0, 1000.0, 3.0}), 202.8);
}

}  // namespace
}  // namespace omnicam
