#include "texture.h"

#include <gtest/gtest.h>

#include "image.h"

namespace omnicam {
namespace {

TEST(Texture, BilinearWithTexelCentresAtHalf) {
  // 2×1 texture: left texel 0, right texel 1. Texel centres sit at u = 0.25 and 0.75.
  const Texture t(2, 1, {0, 0, 0, 1, 1, 1});
  EXPECT_FLOAT_EQ(t.sample(0.25, 0.5).x(), 0.0f);
  EXPECT_FLOAT_EQ(t.sample(0.75, 0.5).x(), 1.0f);
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.5).x(), 0.5f);
  // Repeat wrapping: u = 0 is halfway between the last and the first texel.
  EXPECT_FLOAT_EQ(t.sample(0.0, 0.5).x(), 0.5f);
  EXPECT_FLOAT_EQ(t.sample(1.25, 0.5).x(), 0.0f);
}

TEST(Texture, VZeroIsTheBottomRow) {
  const Texture t(1, 2, {1, 1, 1, 0, 0, 0});  // top row white, bottom row black
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.25).x(), 0.0f);
  EXPECT_FLOAT_EQ(t.sample(0.5, 0.75).x(), 1.0f);
}

TEST(Srgb, RoundTripsAndKnownValues) {
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-6);
  EXPECT_NEAR(linearToSrgb(0.214041f), 0.5f, 1e-6);
  for (float v = 0.0f; v <= 1.0f; v += 0.01f) EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-5);
}

}  // namespace
}  // namespace omnicam
