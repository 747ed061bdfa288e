#include "image_compare.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "errors.h"
#include "number_format.h"

namespace omnicam {

namespace {

// SSIM's windows: 8×8 pixels, one every 4 pixels across and down.
constexpr int kSsimWindow = 8, kSsimStride = 4;
// Rows read at once when comparing from files.
constexpr int kBandRows = 32;

bool included(const float* a, const float* b, bool discOnly) { return !discOnly || (a[3] >= 0.999f && b[3] >= 0.999f); }

}  // namespace

RowComparison::RowComparison(int widthA, int heightA, int widthB, int heightB, const CompareOptions& options)
    : width_(widthA), height_(heightA), options_(options) {
  if (widthA != widthB || heightA != heightB)
    throw InputError("compare: image sizes differ (" + std::to_string(widthA) + "x" + std::to_string(heightA) + " vs " +
                     std::to_string(widthB) + "x" + std::to_string(heightB) + ")");
  keptA_.resize(static_cast<size_t>(width_) * 4 * kSsimWindow);
  keptB_.resize(keptA_.size());
}

void RowComparison::addRows(const float* a, const float* b, int count) {
  const size_t row = static_cast<size_t>(width_) * 4;
  for (int k = 0; k < count; ++k) addRow(a + k * row, b + k * row);
}

namespace {

// `row` (RGBA floats) with every value that is not finite made 0, as the image decoder reads it
// from a file; returns how many pixels had one.
long finiteRow(const float* row, int width, std::vector<float>& out) {
  out.assign(row, row + static_cast<size_t>(width) * 4);
  long nonFinite = 0;
  for (int i = 0; i < width; ++i) {
    bool finite = true;
    for (float& v : std::span(out).subspan(static_cast<size_t>(i) * 4, 4))
      if (!std::isfinite(v)) v = 0.0f, finite = false;
    nonFinite += !finite;
  }
  return nonFinite;
}

}  // namespace

void RowComparison::addRow(const float* rowA, const float* rowB) {
  const int j = rows_++;
  r_.nonFiniteA += finiteRow(rowA, width_, finiteA_);
  r_.nonFiniteB += finiteRow(rowB, width_, finiteB_);
  const float *a = finiteA_.data(), *b = finiteB_.data();
  for (int i = 0; i < width_; ++i) {
    const float *pa = a + 4 * i, *pb = b + 4 * i;
    if (!included(pa, pb, options_.discOnly)) continue;
    r_.maxAbsAlpha = std::max(r_.maxAbsAlpha, std::abs(static_cast<double>(pa[3]) - pb[3]));
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(pa[c]) - pb[c];
      sumSq_ += d * d;
      worst = std::max(worst, std::abs(d));
    }
    if (worst > r_.maxAbs) r_.maxAbs = worst, r_.maxI = i, r_.maxJ = j;
    over_ += worst > options_.tolerance;
    ++r_.pixels;
    const double la = luminance<double>(pa), lb = luminance<double>(pb);
    whole_.a += la, whole_.b += lb, whole_.aa += la * la, whole_.bb += lb * lb, whole_.ab += la * lb;
  }
  const size_t row = static_cast<size_t>(width_) * 4, slot = static_cast<size_t>(j % kSsimWindow) * row;
  std::copy(a, a + row, keptA_.begin() + static_cast<std::ptrdiff_t>(slot));
  std::copy(b, b + row, keptB_.begin() + static_cast<std::ptrdiff_t>(slot));
  const int top = j - (kSsimWindow - 1);
  if (top >= 0 && top % kSsimStride == 0) addSsimWindows(top);
}

// SSIM (Wang et al. 2004) of one window's luminance sums over n pixels, L = 1.
double RowComparison::LumaSums::ssim(double n) const {
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  const double ma = a / n, mb = b / n;
  const double va = aa / n - ma * ma, vb = bb / n - mb * mb, cov = ab / n - ma * mb;
  return ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
}

// Mean SSIM of the luminance: the windows whose top row is `top`, left to right; a window with a
// pixel outside the disc (discOnly) is left out.
void RowComparison::addSsimWindows(int top) {
  const size_t row = static_cast<size_t>(width_) * 4;
  for (int x = 0; x + kSsimWindow <= width_; x += kSsimStride) {
    LumaSums sums;
    bool all = true;
    for (int j = top; j < top + kSsimWindow && all; ++j) {
      const size_t slot = static_cast<size_t>(j % kSsimWindow) * row;
      for (int i = x; i < x + kSsimWindow; ++i) {
        const float *pa = &keptA_[slot + 4 * static_cast<size_t>(i)], *pb = &keptB_[slot + 4 * static_cast<size_t>(i)];
        if (!included(pa, pb, options_.discOnly)) {
          all = false;
          break;
        }
        const double va = luminance<double>(pa), vb = luminance<double>(pb);
        sums.a += va, sums.b += vb, sums.aa += va * va, sums.bb += vb * vb, sums.ab += va * vb;
      }
    }
    if (!all) continue;
    ssimSum_ += sums.ssim(kSsimWindow * kSsimWindow);
    ++windows_;
  }
}

CompareResult RowComparison::result() const {
  if (rows_ != height_)
    throw std::logic_error("compare: " + std::to_string(rows_) + " of " + std::to_string(height_) + " rows given");
  if (r_.pixels == 0) throw InputError("compare: no pixels to compare");
  CompareResult r = r_;
  r.rmse = std::sqrt(sumSq_ / (3.0 * r.pixels));
  r.psnrDb = r.rmse > 0.0 ? 20.0 * std::log10(1.0 / r.rmse) : INFINITY;
  r.fracOverTol = static_cast<double>(over_) / r.pixels;
  // Where no 8×8 window fits (an image, or a disc, smaller than that), the compared pixels are
  // one window.
  r.ssim = windows_ ? ssimSum_ / windows_ : whole_.ssim(static_cast<double>(r.pixels));
  return r;
}

std::string nonFiniteText(const CompareResult& r) {
  return "not finite: " + std::to_string(r.nonFiniteA) + " pixels of A, " + std::to_string(r.nonFiniteB) +
         " of B (NaN or inf, read as 0)";
}

std::string alphaText(const CompareResult& r) {
  if (!r.alphaCompared) return "not compared (an image has no alpha channel)";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", r.maxAbsAlpha);
  return text;
}

std::vector<std::string> CompareThresholds::failures(const CompareResult& r) const {
  std::vector<std::string> failed;
  if (minPsnrDb && r.psnrDb < *minPsnrDb) failed.push_back("psnr_db < " + shortNumber(*minPsnrDb));
  if (maxRmse && r.rmse > *maxRmse) failed.push_back("rmse > " + shortNumber(*maxRmse));
  if (maxAbs && r.maxAbs > *maxAbs) failed.push_back("max_abs > " + shortNumber(*maxAbs));
  if (maxAbs && r.alphaCompared && r.maxAbsAlpha > *maxAbs) failed.push_back("max_abs_alpha > " + shortNumber(*maxAbs));
  if (any() && !r.allFinite()) failed.push_back(nonFiniteText(r));
  return failed;
}

CompareResult compareImages(const ImageRGBA& a, const ImageRGBA& b, const CompareOptions& options) {
  RowComparison comparison(a.width, a.height, b.width, b.height, options);
  comparison.addRows(a.pixels.data(), b.pixels.data(), a.height);
  return comparison.result();
}

namespace {

// The mirror disc is where both alphas are 1: with no alpha in either image there is none.
void checkDiscIsKnown(const CompareOptions& options, bool alphaA, bool alphaB) {
  if (options.discOnly && !alphaA && !alphaB)
    throw InputError("comparing inside the mirror disc: neither image has an alpha channel, which marks the disc");
}

}  // namespace

CompareResult compareImageRows(ImageRowReader& a, ImageRowReader& b, const CompareOptions& options) {
  a.requireColour();
  b.requireColour();
  checkDiscIsKnown(options, a.holdsAlpha(), b.holdsAlpha());
  RowComparison comparison(a.width(), a.height(), b.width(), b.height(), options);
  std::vector<float> bandA(static_cast<size_t>(a.width()) * 4 * kBandRows), bandB(bandA.size());
  for (int first = 0; first < a.height(); first += kBandRows) {
    const int count = std::min(kBandRows, a.height() - first);
    a.readRows(first, count, bandA.data());
    b.readRows(first, count, bandB.data());
    comparison.addRows(bandA.data(), bandB.data(), count);
  }
  CompareResult r = comparison.result();
  r.nonFiniteA += a.nonFinitePixels(), r.nonFiniteB += b.nonFinitePixels();
  if (!a.holdsAlpha() || !b.holdsAlpha()) r.alphaCompared = false, r.maxAbsAlpha = 0.0;
  return r;
}

ColourImagePair readColourImages(ImageRowReader& a, ImageRowReader& b) {
  a.requireColour();
  b.requireColour();
  ColourImagePair pair{a.readRemaining(), b.readRemaining()};
  pair.nonFiniteA = a.nonFinitePixels(), pair.nonFiniteB = b.nonFinitePixels();
  pair.alphaA = a.holdsAlpha(), pair.alphaB = b.holdsAlpha();
  return pair;
}

CompareResult compareImagePair(const ColourImagePair& pair, const CompareOptions& options) {
  checkDiscIsKnown(options, pair.alphaA, pair.alphaB);
  CompareResult r = compareImages(pair.a, pair.b, options);
  r.nonFiniteA += pair.nonFiniteA, r.nonFiniteB += pair.nonFiniteB;
  if (!pair.alphaA || !pair.alphaB) r.alphaCompared = false, r.maxAbsAlpha = 0.0;
  return r;
}

int64_t imageRowsCompareBytes(const ImageRowReader& a, const ImageRowReader& b) {
  // Each side: a band of decoded rows and its RGBA, the 8 rows SSIM keeps, and what a file that
  // cannot be read by rows holds whole.
  return (a.rowBytes() + b.rowBytes()) * kBandRows + static_cast<int64_t>(a.width()) * 16 * kSsimWindow * 2 + a.wholeBytes() +
         b.wholeBytes();
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
          {"max_abs_alpha", r.alphaCompared ? nlohmann::json(r.maxAbsAlpha) : nlohmann::json(nullptr)},
          {"frac_over_tol", r.fracOverTol},
          {"pixels", r.pixels},
          {"non_finite_pixels", {r.nonFiniteA, r.nonFiniteB}}};
}

ImageRGBA boxDownsample(const ImageRGBA& large, int n) {
  if (n < 1 || large.width % n != 0 || large.height % n != 0)
    throw InputError("box-downsampling by " + std::to_string(n) + ": the image is " + std::to_string(large.width) + "x" +
                     std::to_string(large.height) + ", not a whole multiple");
  ImageRGBA small(large.width / n, large.height / n);
  const double weight = 1.0 / (static_cast<double>(n) * n);
  for (int j = 0; j < small.height; ++j)
    for (int i = 0; i < small.width; ++i) {
      double sum[4] = {0.0, 0.0, 0.0, 0.0};
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const float* px = large.at(i * n + a, j * n + b);
          for (int c = 0; c < 4; ++c) sum[c] += px[c];
        }
      float* out = small.at(i, j);
      for (int c = 0; c < 4; ++c) out[c] = static_cast<float>(sum[c] * weight);
    }
  return small;
}

std::optional<int> wholeMultiple(int smallWidth, int smallHeight, int largeWidth, int largeHeight) {
  if (smallWidth <= 0 || smallHeight <= 0 || largeWidth % smallWidth != 0 || largeHeight % smallHeight != 0) return std::nullopt;
  const int n = largeWidth / smallWidth;
  if (n < 2 || largeHeight / smallHeight != n) return std::nullopt;
  return n;
}

}  // namespace omnicam
