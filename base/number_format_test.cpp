// Report numbers: a fixed count of decimals, rounded half away as printf does, in any locale.
#include "number_format.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <locale>

namespace omnicam {
namespace {

TEST(FixedDecimals, RoundsToTheGivenDecimalsAsPrintfDoes) {
  EXPECT_EQ(fixedDecimals(3.14159, 2), "3.14");
  EXPECT_EQ(fixedDecimals(2.5, 0), "2");      // round half to even: the binary value is exactly 2.5
  EXPECT_EQ(fixedDecimals(0.125, 2), "0.12");  // exactly representable: to even
  EXPECT_EQ(fixedDecimals(-1.0, 3), "-1.000");
  EXPECT_EQ(fixedDecimals(1e6, 1), "1000000.0");
  for (double v : {0.1, 12.345, 99.995, 1.0 / 3.0}) {
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.*f", 2, v);
    EXPECT_EQ(fixedDecimals(v, 2), expected) << v;
  }
}

TEST(FixedDecimals, IgnoresTheGlobalLocale) {
  struct Comma : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
  };
  const std::locale before = std::locale::global(std::locale(std::locale::classic(), new Comma));
  EXPECT_EQ(fixedDecimals(1.5, 1), "1.5");
  std::locale::global(before);
}

// YAML 1.1 loaders read these as floats (PyYAML: an exponent needs a '.', a whole number one too), and a signed zero
// (a rotation matrix's exact zeros) is written as the 0 it is.
TEST(YamlFloat, WritesWhatYamlLoadersReadAsTheSameFloat) {
  EXPECT_EQ(yamlFloat(0.1), "0.1");
  EXPECT_EQ(yamlFloat(1e-05), "1.0e-05");
  EXPECT_EQ(yamlFloat(1e+20), "1.0e+20");
  EXPECT_EQ(yamlFloat(-0.0), "0.0");
  EXPECT_EQ(yamlFloat(-2.5), "-2.5");
  EXPECT_EQ(yamlFloat(500.0), "500.0");
  EXPECT_EQ(yamlFloat(10.0), "10.0");
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {
TEST(CountOf, TheNounIsSingularForOneOnly) {
  EXPECT_EQ(countOf(1, "frame"), "1 frame");
  EXPECT_EQ(countOf(0, "frame"), "0 frames");
  EXPECT_EQ(countOf(2, "frame"), "2 frames");
  EXPECT_EQ(countOf(-1, "frame"), "-1 frames");
}
}  // namespace
}  // namespace omnicam
