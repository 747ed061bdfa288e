#include "render_noise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "errors.h"

namespace omnicam {

namespace {

// 8-bit sRGB, as a PNG of the frame would hold it.
std::vector<uint8_t> srgb8(const ImageRGBA& image) {
  std::vector<uint8_t> out(static_cast<size_t>(image.width) * image.height * 3);
  for (size_t p = 0; p < static_cast<size_t>(image.width) * image.height; ++p)
    for (int c = 0; c < 3; ++c) {
      const float v = std::clamp(linearToSrgb(image.pixels[p * 4 + c]), 0.0f, 1.0f);
      out[p * 3 + c] = static_cast<uint8_t>(std::lround(v * 255.0f));
    }
  return out;
}

// |value − median of its 3×3 neighbourhood| for channel c (edges clamp).
int distanceFromMedian(const std::vector<uint8_t>& image, int width, int height, int i, int j, int c) {
  std::array<uint8_t, 9> window{};
  int n = 0;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int x = std::clamp(i + di, 0, width - 1), y = std::clamp(j + dj, 0, height - 1);
      window[static_cast<size_t>(n++)] = image[(static_cast<size_t>(y) * width + x) * 3 + c];
    }
  std::nth_element(window.begin(), window.begin() + 4, window.end());
  return std::abs(static_cast<int>(image[(static_cast<size_t>(j) * width + i) * 3 + c]) - window[4]);
}

}  // namespace

RenderNoise measureRenderNoise(const ImageRGBA& frame, const ImageRGBA& reference, int outlierLevels) {
  if (frame.width != reference.width || frame.height != reference.height)
    throw InputError("render noise: the frame is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                     ", the reference " + std::to_string(reference.width) + "x" + std::to_string(reference.height));
  const std::vector<uint8_t> a = srgb8(frame), b = srgb8(reference);
  const int w = frame.width, h = frame.height;
  RenderNoise noise;
  double squared = 0.0;
  long outliers = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (reference.at(i, j)[3] < 0.999f) continue;  // the rim and beyond
      ++noise.pixels;
      bool outlier = false;
      for (int c = 0; c < 3; ++c) {
        const size_t k = (static_cast<size_t>(j) * w + i) * 3 + static_cast<size_t>(c);
        const double d = static_cast<double>(a[k]) - b[k];
        squared += d * d;
        outlier = outlier || distanceFromMedian(a, w, h, i, j, c) - distanceFromMedian(b, w, h, i, j, c) > outlierLevels;
      }
      outliers += outlier;
    }
  if (noise.pixels == 0) throw InputError("render noise: no pixel inside the mirror disc");
  const double mse = squared / (3.0 * static_cast<double>(noise.pixels));
  noise.psnrDb = mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
  noise.outlierShare = static_cast<double>(outliers) / static_cast<double>(noise.pixels);
  return noise;
}

double psnrAgainstConvergedFromPair(double pairPsnrDb) { return pairPsnrDb + 10.0 * std::log10(2.0); }

}  // namespace omnicam
