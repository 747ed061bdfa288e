#pragma once
// Pixel-by-pixel comparison of two renders (OpenImageIO idiff style): RMSE, PSNR, SSIM,
// max abs error and where, fraction of pixels over a tolerance; optionally only inside the
// mirror disc. Values are linear RGB; alpha is not compared.
#include <nlohmann/json.hpp>
#include <optional>

#include "image.h"

namespace omnicam {

struct CompareOptions {
  double tolerance = 1.0 / 255.0;  // per-channel absolute difference counted as "over"
  bool discOnly = false;           // only pixels wholly inside the mirror disc (alpha = 1 in both)
};

struct CompareResult {
  double rmse = 0.0, psnrDb = 0.0, ssim = 1.0, maxAbs = 0.0, fracOverTol = 0.0;
  int maxI = 0, maxJ = 0;
  long pixels = 0;
};

// Throws InputError if the sizes differ or no pixel is compared.
CompareResult compareImages(const ImageRGBA& a, const ImageRGBA& b, const CompareOptions& options = {});
// |a − b| (max over channels) as a heat map: black 0 → red → yellow → white at `scale`.
ImageRGBA differenceHeatmap(const ImageRGBA& a, const ImageRGBA& b, double scale);
// A scalar field as the same heat ramp (black 0 → red → yellow → white at `scale`); NaN is
// drawn transparent black.
ImageRGBA scalarHeatmap(const std::vector<float>& values, int width, int height, double scale);
nlohmann::json compareResultToJson(const CompareResult& r);

}  // namespace omnicam
