// The classifier on inputs whose answer is known: hand-set histogram counts (Eqs. 3.8–3.10 by
// hand), and synthetic images of a cyan disc on a noisy background.
#include "colour_classifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace omnicam {
namespace {

TEST(ColourClassifier, LikelihoodRatioIsTheRatioOfNormalisedCounts) {
  ColourHistogramClassifier c(4);  // codes 0–63 → bin 0, 64–127 → 1, ...
  const Rgb8 a{10, 200, 250}, b{200, 10, 10}, unseen{100, 100, 100};
  c.addPositive(a, 3);
  c.addPositive(b, 1);
  c.addNegative(a, 1);
  c.addNegative(b, 3);
  EXPECT_DOUBLE_EQ(c.likelihoodRatio(a), (3.0 / 4.0) / (1.0 / 4.0));
  EXPECT_DOUBLE_EQ(c.likelihoodRatio(b), (1.0 / 4.0) / (3.0 / 4.0));
  EXPECT_DOUBLE_EQ(c.likelihoodRatio(Rgb8{63, 255, 192}), c.likelihoodRatio(a));  // same bin as a
  EXPECT_EQ(c.likelihoodRatio(unseen), 0.0);
  EXPECT_TRUE(c.positive(a, 1.0));
  EXPECT_FALSE(c.positive(b, 1.0));
  EXPECT_TRUE(c.positive(b, 0.3));  // Θ trades detections for false positives
  c.addPositive(unseen);
  EXPECT_TRUE(std::isinf(c.likelihoodRatio(unseen)));
}

// A cyan disc on a grey, noisy background; `centre` moves it between images.
ImageRGBA discImage(int size, double cx, double cy, std::mt19937_64& rng, std::vector<uint8_t>* labels) {
  std::normal_distribution<float> noise(0.0f, 0.02f);
  ImageRGBA image(size, size);
  if (labels) labels->assign(static_cast<size_t>(size) * size, 0);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const bool inside = std::hypot(i + 0.5 - cx, j + 0.5 - cy) < 10.0;
      const float base[3] = {inside ? 0.02f : 0.3f, inside ? 0.6f : 0.3f, inside ? 0.8f : 0.3f};
      float* px = image.at(i, j);
      for (int c = 0; c < 3; ++c) px[c] = std::clamp(base[c] + noise(rng), 0.0f, 1.0f);
      px[3] = 1.0f;
      if (labels && inside) (*labels)[static_cast<size_t>(j) * size + i] = 1;
    }
  return image;
}

TEST(ColourClassifier, CoarsenedCountsWhatTrainingAtTheCoarseResolutionCounts) {
  // Random colours trained at 32 and at 8 bins: the 32-bin histogram coarsened to 8 bins agrees
  // with the 8-bin one at every code (codes 0–31 → coarse bin 0, …), and by hand at two codes.
  std::mt19937 random(7);
  std::uniform_int_distribution<int> code(0, 255);
  ColourHistogramClassifier fine(32), direct(8);
  for (int k = 0; k < 5000; ++k) {
    const Rgb8 colour{static_cast<uint8_t>(code(random)), static_cast<uint8_t>(code(random) / 2), static_cast<uint8_t>(code(random))};
    const bool positive = colour[0] > 150 && k % 3 != 0;
    (positive ? fine.addPositive(colour) : fine.addNegative(colour));
    (positive ? direct.addPositive(colour) : direct.addNegative(colour));
  }
  const ColourHistogramClassifier coarse = fine.coarsened(8);
  EXPECT_EQ(coarse.binsPerChannel(), 8);
  EXPECT_EQ(coarse.positiveTotal(), fine.positiveTotal());
  EXPECT_EQ(coarse.negativeTotal(), fine.negativeTotal());
  for (int r = 0; r < 256; r += 5)
    for (int g = 0; g < 256; g += 7)
      for (int b = 0; b < 256; b += 11) {
        const Rgb8 colour{static_cast<uint8_t>(r), static_cast<uint8_t>(g), static_cast<uint8_t>(b)};
        ASSERT_EQ(coarse.positiveCount(colour), direct.positiveCount(colour));
        ASSERT_EQ(coarse.negativeCount(colour), direct.negativeCount(colour));
      }
  ColourHistogramClassifier byHand(4);
  byHand.addPositive(Rgb8{0, 0, 0}, 2);      // fine bins (0,0,0) and (1,1,1) of 4 share coarse bin (0,0,0) of 2
  byHand.addPositive(Rgb8{127, 127, 127}, 3);
  byHand.addNegative(Rgb8{128, 0, 0}, 5);    // fine bin (2,0,0) → coarse (1,0,0)
  const ColourHistogramClassifier halved = byHand.coarsened(2);
  EXPECT_EQ(halved.positiveCount(Rgb8{10, 100, 50}), 5u);
  EXPECT_EQ(halved.negativeCount(Rgb8{255, 127, 0}), 5u);
  EXPECT_EQ(halved.positiveCount(Rgb8{255, 255, 255}), 0u);
  EXPECT_THROW(byHand.coarsened(3), std::invalid_argument);
  EXPECT_THROW(byHand.coarsened(8), std::invalid_argument);
  EXPECT_THROW(byHand.coarsened(0), std::invalid_argument);
  // A factor that is not a power of two: 12 bins (codes 0–21 → 0, 22–42 → 1, …) to 4 (0–63 → 0, …).
  ColourHistogramClassifier twelve(12), four(4);
  for (int c = 0; c < 256; c += 3) {
    const Rgb8 colour{static_cast<uint8_t>(c), static_cast<uint8_t>(255 - c), static_cast<uint8_t>((c * 7) % 256)};
    twelve.addPositive(colour, static_cast<uint64_t>(c % 5 + 1));
    four.addPositive(colour, static_cast<uint64_t>(c % 5 + 1));
  }
  const ColourHistogramClassifier thirds = twelve.coarsened(4);
  for (int c = 0; c < 256; ++c) {
    const Rgb8 colour{static_cast<uint8_t>(c), static_cast<uint8_t>(255 - c), static_cast<uint8_t>((c * 7) % 256)};
    ASSERT_EQ(thirds.positiveCount(colour), four.positiveCount(colour)) << c;
  }
}

TEST(ColourClassifier, ResolutionsAreTheTrainedOneAndItsExactHalvings) {
  EXPECT_EQ(resolutionAndHalvings(32, 8), (std::vector<int>{32, 16, 8}));
  EXPECT_EQ(resolutionAndHalvings(24, 8), (std::vector<int>{24, 12}));
  EXPECT_EQ(resolutionAndHalvings(136, 8), (std::vector<int>{136, 68, 34, 17}));
  EXPECT_EQ(resolutionAndHalvings(7, 8), (std::vector<int>{7}));
  EXPECT_EQ(resolutionAndHalvings(2, 8), (std::vector<int>{2}));
  EXPECT_EQ(resolutionAndHalvings(256, 8), (std::vector<int>{256, 128, 64, 32, 16, 8}));
}

TEST(ColourClassifier, LearnsACyanDiscAndFindsItElsewhere) {
  std::mt19937_64 rng(5);
  std::vector<uint8_t> labels, truth;
  ColourHistogramClassifier c(32);
  c.train(discImage(64, 20, 20, rng, &labels), labels);
  EXPECT_GT(c.positiveTotal(), 250u);
  const ImageRGBA test = discImage(64, 40, 44, rng, &truth);
  const std::vector<uint8_t> mask = c.classify(test, 1.0);
  int wrong = 0;
  for (size_t p = 0; p < mask.size(); ++p) wrong += mask[p] != truth[p];
  EXPECT_LT(wrong, 20) << "of " << mask.size() << " pixels";
}

}  // namespace
}  // namespace omnicam
