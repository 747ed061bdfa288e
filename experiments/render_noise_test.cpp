// render_noise: against closed-form PSNRs of 8-bit levels, isolated specks and shared edges.
#include "render_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "errors.h"

namespace omnicam {
namespace {

// An image whose pixels encode to the given 8-bit sRGB level exactly; alpha 1.
ImageRGBA levels(int size, const std::function<int(int, int)>& level) {
  ImageRGBA image(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      float* p = image.at(i, j);
      p[0] = p[1] = p[2] = srgbToLinear(static_cast<float>(level(i, j)) / 255.0f);
      p[3] = 1.0f;
    }
  return image;
}

TEST(RenderNoise, IdenticalImagesHaveNoNoise) {
  const ImageRGBA a = levels(16, [](int i, int j) { return (i * 7 + j * 13) % 256; });
  const RenderNoise n = measureRenderNoise(a, a);
  EXPECT_EQ(n.pixels, 256);
  EXPECT_EQ(n.outlierShare, 0.0);
  EXPECT_GE(n.psnrDb, 99.0);
}

TEST(RenderNoise, AUniformShiftOfDLevelsIsTwentyLogOf255OverD) {
  for (int d : {1, 4, 20}) {
    const RenderNoise n = measureRenderNoise(levels(12, [&](int, int) { return 100 + d; }), levels(12, [](int, int) { return 100; }));
    EXPECT_NEAR(n.psnrDb, 20.0 * std::log10(255.0 / d), 1e-9) << d;
    EXPECT_EQ(n.outlierShare, 0.0) << "a shift is no speckle";
  }
}

TEST(RenderNoise, AnIsolatedSpeckIsOneOutlierAndEdgesTheReferenceSharesAreNone) {
  // The reference: two halves 40 and 200 (a hard edge every 3×3 window across it sees).
  const auto halves = [](int i, int) { return i < 10 ? 40 : 200; };
  const ImageRGBA reference = levels(20, halves);
  const ImageRGBA speck = levels(20, [&](int i, int j) { return i == 4 && j == 7 ? 255 : halves(i, j); });
  const RenderNoise n = measureRenderNoise(speck, reference);
  EXPECT_DOUBLE_EQ(n.outlierShare, 1.0 / 400.0);
  EXPECT_NEAR(n.psnrDb, 10.0 * std::log10(255.0 * 255.0 / (215.0 * 215.0 / 400.0)), 1e-9);
  // A speck of fewer than kOutlierLevels levels is noise, not an outlier.
  const ImageRGBA faint = levels(20, [&](int i, int j) { return i == 4 && j == 7 ? 40 + kOutlierLevels : halves(i, j); });
  EXPECT_EQ(measureRenderNoise(faint, reference).outlierShare, 0.0);
}

TEST(RenderNoise, OnlyPixelsInsideTheDiscCount) {
  ImageRGBA reference = levels(8, [](int, int) { return 50; });
  ImageRGBA frame = levels(8, [](int i, int) { return i < 4 ? 50 : 250; });
  for (int j = 0; j < 8; ++j)
    for (int i = 4; i < 8; ++i) reference.at(i, j)[3] = 0.5f;  // beyond the rim
  const RenderNoise n = measureRenderNoise(frame, reference);
  EXPECT_EQ(n.pixels, 32);
  EXPECT_GE(n.psnrDb, 99.0);
}

TEST(RenderNoise, MismatchedSizesOrNoDiscAreInputErrors) {
  EXPECT_THROW(measureRenderNoise(levels(8, [](int, int) { return 0; }), levels(9, [](int, int) { return 0; })), InputError);
  ImageRGBA none(4, 4);  // alpha 0 everywhere
  EXPECT_THROW(measureRenderNoise(none, none), InputError);
}

TEST(RenderNoise, ASeedPairPredictsThePsnrAgainstTheTruth) {
  // Two frames with independent Gaussian noise of 6 levels around a known truth.
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 6.0);
  const auto truthLevel = [](int i, int j) { return 60 + (i * 3 + j) % 120; };
  auto noisy = [&](int i, int j) { return static_cast<int>(std::lround(std::clamp(truthLevel(i, j) + noise(random), 0.0, 255.0))); };
  const ImageRGBA truth = levels(200, truthLevel), a = levels(200, noisy), b = levels(200, noisy);
  const double pair = measureRenderNoise(a, b).psnrDb;
  EXPECT_NEAR(psnrAgainstConvergedFromPair(pair), measureRenderNoise(a, truth).psnrDb, 0.15);
  EXPECT_NEAR(measureRenderNoise(a, truth).psnrDb, 20.0 * std::log10(255.0 / 6.0), 0.15);
}

}  // namespace
}  // namespace omnicam
