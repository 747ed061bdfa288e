#include "colour_classifier.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "memory_budget.h"

namespace omnicam {

Rgb8 rgb8FromPixel(const float* rgba) {
  Rgb8 out;
  const float alpha = rgba[3];
  for (int c = 0; c < 3; ++c) {
    const float linear = alpha > 0.0f ? rgba[c] / alpha : 0.0f;
    out[c] = static_cast<uint8_t>(std::lround(std::clamp(linearToSrgb(linear), 0.0f, 1.0f) * 255.0f));
  }
  return out;
}

std::vector<int> resolutionAndHalvings(int bins, int smallest) {
  std::vector<int> out = {bins};
  while (out.back() % 2 == 0 && out.back() / 2 >= smallest) out.push_back(out.back() / 2);
  return out;
}

ColourHistogramClassifier::ColourHistogramClassifier(int binsPerChannel) : bins_(binsPerChannel) {
  if (bins_ < 1 || bins_ > 256) throw std::invalid_argument("bins per channel must be in [1, 256]");
  const size_t cells = static_cast<size_t>(bins_) * bins_ * bins_;
  // 256 bins a channel are 268 MB of counts a classifier, and an experiment holds several (the
  // usual 32 bins, 0.5 MB, are not worth reading /proc for).
  const auto bytes = static_cast<int64_t>(2 * cells * sizeof(uint64_t));
  if (bytes > (int64_t{64} << 20)) requireMemory(bytes, "a colour histogram classifier of " + std::to_string(bins_) + "³ bins");
  positive_.assign(cells, 0);
  negative_.assign(cells, 0);
}

size_t ColourHistogramClassifier::bin(const Rgb8& colour) const {
  size_t index = 0;
  for (int c = 0; c < 3; ++c) index = index * bins_ + static_cast<size_t>(colour[c]) * bins_ / 256;
  return index;
}

void ColourHistogramClassifier::addPositive(const Rgb8& colour, uint64_t count) {
  positive_[bin(colour)] += count;
  positiveTotal_ += count;
}

void ColourHistogramClassifier::addNegative(const Rgb8& colour, uint64_t count) {
  negative_[bin(colour)] += count;
  negativeTotal_ += count;
}

void ColourHistogramClassifier::train(const ImageRGBA& image, const std::vector<uint8_t>& labels) {
  if (labels.size() != static_cast<size_t>(image.width) * image.height)
    throw std::invalid_argument("train: one label per pixel");
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const uint8_t label = labels[static_cast<size_t>(j) * image.width + i];
      if (label == 1) addPositive(rgb8FromPixel(image.at(i, j)));
      else if (label == 0) addNegative(rgb8FromPixel(image.at(i, j)));
    }
}

ColourHistogramClassifier ColourHistogramClassifier::coarsened(int binsPerChannel) const {
  if (binsPerChannel < 1 || binsPerChannel > bins_ || bins_ % binsPerChannel != 0)
    throw std::invalid_argument("coarsened: " + std::to_string(binsPerChannel) + " bins do not divide " + std::to_string(bins_));
  ColourHistogramClassifier coarse(binsPerChannel);
  const size_t fine = static_cast<size_t>(bins_), factor = fine / static_cast<size_t>(binsPerChannel);
  const size_t coarseBins = static_cast<size_t>(binsPerChannel);
  for (size_t r = 0; r < fine; ++r)
    for (size_t g = 0; g < fine; ++g)
      for (size_t b = 0; b < fine; ++b) {
        const size_t from = (r * fine + g) * fine + b;
        const size_t to = ((r / factor) * coarseBins + g / factor) * coarseBins + b / factor;
        coarse.positive_[to] += positive_[from];
        coarse.negative_[to] += negative_[from];
      }
  coarse.positiveTotal_ = positiveTotal_;
  coarse.negativeTotal_ = negativeTotal_;
  return coarse;
}

double ColourHistogramClassifier::likelihoodRatio(const Rgb8& colour) const {
  const size_t b = bin(colour);
  if (positiveTotal_ == 0 || positive_[b] == 0) return 0.0;
  if (negativeTotal_ == 0 || negative_[b] == 0) return std::numeric_limits<double>::infinity();
  return (static_cast<double>(positive_[b]) / positiveTotal_) / (static_cast<double>(negative_[b]) / negativeTotal_);
}

bool ColourHistogramClassifier::positive(const Rgb8& colour, double theta) const {
  const double ratio = likelihoodRatio(colour);
  return ratio > 0.0 && ratio >= theta;
}

std::vector<uint8_t> ColourHistogramClassifier::classify(const ImageRGBA& image, double theta) const {
  std::vector<uint8_t> mask(static_cast<size_t>(image.width) * image.height, 0);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      mask[static_cast<size_t>(j) * image.width + i] = positive(rgb8FromPixel(image.at(i, j)), theta);
  return mask;
}

}  // namespace omnicam
