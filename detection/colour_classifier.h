#pragma once
// The thesis' colour-histogram pixel classifier (§3.4.1, Eqs. 3.8–3.10, after Jones & Rehg):
// a 3-D RGB histogram of positive pixels and one of negative pixels, each normalised to a
// probability; a colour is positive when P(rgb | positive) / P(rgb | negative) ≥ Θ.
// Colours are 8-bit sRGB codes, what a camera delivers (and what PNG frames hold).
#include <array>
#include <cstdint>
#include <vector>

#include "image.h"

namespace omnicam {

using Rgb8 = std::array<uint8_t, 3>;

// The 8-bit sRGB code of a linear, premultiplied pixel (as PNG encoding rounds it).
Rgb8 rgb8FromPixel(const float* rgba);

// `bins` and each exact halving of it not below `smallest` (32, 8 → 32, 16, 8; 24, 8 → 24, 12;
// 7, 8 → 7): the resolutions a classifier trained at `bins` coarsens to by halving.
std::vector<int> resolutionAndHalvings(int bins, int smallest);

class ColourHistogramClassifier {
 public:
  // `binsPerChannel` in [1, 256]: code c falls in bin c·bins/256.
  explicit ColourHistogramClassifier(int binsPerChannel);

  void addPositive(const Rgb8& colour, uint64_t count = 1);
  void addNegative(const Rgb8& colour, uint64_t count = 1);
  // Every pixel of `image` whose `label` is 1 (positive) or 0 (negative); 255 = ignore (e.g.
  // beyond the mirror rim). `labels` has one entry per pixel.
  void train(const ImageRGBA& image, const std::vector<uint8_t>& labels);

  // P(rgb | positive) / P(rgb | negative) (Eqs. 3.9): +∞ for a colour seen only as positive,
  // 0 for one never seen as positive (and for an untrained class).
  double likelihoodRatio(const Rgb8& colour) const;
  // Eq. 3.10; a colour never seen as positive is never positive, whatever Θ.
  bool positive(const Rgb8& colour, double theta) const;
  // One mask entry per pixel: 1 positive, 0 not.
  std::vector<uint8_t> classify(const ImageRGBA& image, double theta) const;

  // The same training at `binsPerChannel` bins, which must divide this one's: each coarse bin
  // holds its fine bins' counts (bin c·bins/256 of a code c nests in the finer bin, so this is
  // exactly what training at the coarse resolution would count).
  ColourHistogramClassifier coarsened(int binsPerChannel) const;

  int binsPerChannel() const { return bins_; }
  uint64_t positiveTotal() const { return positiveTotal_; }
  uint64_t negativeTotal() const { return negativeTotal_; }
  uint64_t positiveCount(const Rgb8& colour) const { return positive_[bin(colour)]; }
  uint64_t negativeCount(const Rgb8& colour) const { return negative_[bin(colour)]; }

 private:
  size_t bin(const Rgb8& colour) const;
  int bins_;
  std::vector<uint64_t> positive_, negative_;
  uint64_t positiveTotal_ = 0, negativeTotal_ = 0;
};

}  // namespace omnicam
