#include "cpu_independent_math.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

TEST(PlainMath, TheTunableIsAddedToWhatTheEnvironmentHolds) {
  EXPECT_EQ(tunablesForPlainMath(nullptr), "glibc.cpu.hwcaps=-FMA,-FMA4");
  EXPECT_EQ(tunablesForPlainMath(""), "glibc.cpu.hwcaps=-FMA,-FMA4");
  EXPECT_EQ(tunablesForPlainMath("glibc.malloc.arena_max=2"), "glibc.malloc.arena_max=2:glibc.cpu.hwcaps=-FMA,-FMA4");
}

TEST(PlainMath, AHwcapsTunableAlreadySetIsLeftAsItIs) {
  // The restarted process finds its own; a user's (even an empty one, glibc's own choice) holds.
  EXPECT_EQ(tunablesForPlainMath("glibc.cpu.hwcaps=-FMA,-FMA4"), "");
  EXPECT_EQ(tunablesForPlainMath("glibc.cpu.hwcaps="), "");
  EXPECT_EQ(tunablesForPlainMath("glibc.malloc.arena_max=2:glibc.cpu.hwcaps=-AVX512F"), "");
}

}  // namespace
}  // namespace omnicam
