#include "image_compare.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "errors.h"

namespace omnicam {

namespace {

bool included(const ImageRGBA& a, const ImageRGBA& b, int i, int j, bool discOnly) {
  return !discOnly || (a.at(i, j)[3] >= 0.999f && b.at(i, j)[3] >= 0.999f);
}

// Mean SSIM (Wang et al. 2004) of the luminance, 8×8 windows with stride 4, L = 1.
double meanSsim(const ImageRGBA& a, const ImageRGBA& b, bool discOnly) {
  auto luma = [](const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; };
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  const int w = 8;
  double sum = 0.0;
  int windows = 0;
  for (int y = 0; y + w <= a.height; y += 4)
    for (int x = 0; x + w <= a.width; x += 4) {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      bool all = true;
      for (int j = y; j < y + w && all; ++j)
        for (int i = x; i < x + w; ++i) {
          if (!included(a, b, i, j, discOnly)) {
            all = false;
            break;
          }
          const double va = luma(a.at(i, j)), vb = luma(b.at(i, j));
          sa += va, sb += vb, saa += va * va, sbb += vb * vb, sab += va * vb;
        }
      if (!all) continue;
      const double n = w * w, ma = sa / n, mb = sb / n;
      const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  return windows ? sum / windows : 1.0;
}

}  // namespace

CompareResult compareImages(const ImageRGBA& a, const ImageRGBA& b, const CompareOptions& options) {
  if (a.width != b.width || a.height != b.height)
    throw InputError("compare: image sizes differ (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  CompareResult r;
  double sumSq = 0.0;
  long over = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      if (!included(a, b, i, j, options.discOnly)) continue;
      double worst = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double d = static_cast<double>(a.at(i, j)[c]) - b.at(i, j)[c];
        sumSq += d * d;
        worst = std::max(worst, std::abs(d));
      }
      if (worst > r.maxAbs) r.maxAbs = worst, r.maxI = i, r.maxJ = j;
      over += worst > options.tolerance;
      ++r.pixels;
    }
  if (r.pixels == 0) throw InputError("compare: no pixels to compare");
  r.rmse = std::sqrt(sumSq / (3.0 * r.pixels));
  r.psnrDb = r.rmse > 0.0 ? 20.0 * std::log10(1.0 / r.rmse) : INFINITY;
  r.fracOverTol = static_cast<double>(over) / r.pixels;
  r.ssim = meanSsim(a, b, options.discOnly);
  return r;
}

ImageRGBA scalarHeatmap(const std::vector<float>& values, int width, int height, double scale) {
  ImageRGBA out(width, height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float v = values[static_cast<size_t>(j) * width + i];
      if (std::isnan(v)) continue;
      const float t = static_cast<float>(std::clamp(v / scale, 0.0, 1.0));
      float* p = out.at(i, j);
      p[0] = std::min(1.0f, 3.0f * t);
      p[1] = std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f);
      p[2] = std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f);
      p[3] = 1.0f;
    }
  return out;
}

ImageRGBA differenceHeatmap(const ImageRGBA& a, const ImageRGBA& b, double scale) {
  std::vector<float> difference(static_cast<size_t>(a.width) * a.height);
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      double d = 0.0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(static_cast<double>(a.at(i, j)[c]) - b.at(i, j)[c]));
      difference[static_cast<size_t>(j) * a.width + i] = static_cast<float>(d);
    }
  return scalarHeatmap(difference, a.width, a.height, scale);
}

nlohmann::json compareResultToJson(const CompareResult& r) {
  return {{"rmse", r.rmse},
          {"psnr_db", std::isfinite(r.psnrDb) ? nlohmann::json(r.psnrDb) : nlohmann::json("inf")},
          {"ssim", r.ssim},
          {"max_abs", r.maxAbs},
          {"max_abs_pixel", {r.maxI, r.maxJ}},
          {"frac_over_tol", r.fracOverTol},
          {"pixels", r.pixels}};
}

}  // namespace omnicam
