#include "texture.h"

#include <gtest/gtest.h>

#include "image.h"

#include <cmath>

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

TEST(Srgb, PngWriterEncodesExactlyLikeTheFormula) {
  // Every 8-bit code the writer picks equals lround(linearToSrgb(v) · 255), read back exactly.
  ImageRGBA img(1024, 1);
  for (int i = 0; i < 1024; ++i) {
    float* p = img.at(i, 0);
    p[0] = i / 1023.0f, p[1] = (i / 1023.0f) * (i / 1023.0f), p[2] = 0.5f * i / 1023.0f, p[3] = 1.0f;
  }
  const std::string path = ::testing::TempDir() + "/srgb_exact.png";
  writeImageAtomic(path, img);
  const ImageRGBA back = readImage(path);
  for (int i = 0; i < 1024; ++i)
    for (int c = 0; c < 3; ++c) {
      const long expected = std::lround(linearToSrgb(img.at(i, 0)[c]) * 255.0f);
      ASSERT_EQ(std::lround(linearToSrgb(back.at(i, 0)[c]) * 255.0f), expected) << i << " " << c;
    }
}

}  // namespace
}  // namespace omnicam
