#pragma once
// Pixel-by-pixel comparison of two renders (OpenImageIO idiff style): RMSE, PSNR, SSIM (mean
// over 8×8 windows a stride of 4 apart; the compared pixels as one window if none fits),
// max abs error and where, fraction of pixels over a tolerance; optionally only inside the
// mirror disc. Values are linear RGB; alpha (the rim's coverage) has its own largest difference,
// and pixels with a value that is not finite are counted per image: a NaN is a result to catch,
// not a value to compare (it counts as 0, as the image decoder reads it from a file).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "image.h"

namespace omnicam {

struct CompareOptions {
  double tolerance = 1.0 / 255.0;  // per-channel absolute difference counted as "over"
  bool discOnly = false;           // only pixels wholly inside the mirror disc (alpha = 1 in both)
};

struct CompareResult {
  double rmse = 0.0, psnrDb = 0.0, ssim = 1.0, maxAbs = 0.0, fracOverTol = 0.0;
  int maxI = 0, maxJ = 0;  // where maxAbs is: column, row
  double maxAbsAlpha = 0.0;
  // Alpha is compared when both images have it: a file without alpha (a POV-Ray or Blender job's
  // render.exr is B, G, R) reads as 1, which is no coverage to compare. maxAbsAlpha is then 0.
  bool alphaCompared = true;
  long pixels = 0;
  long nonFiniteA = 0, nonFiniteB = 0;  // pixels with a NaN or ±∞ colour or alpha, in all of each image
  bool allFinite() const { return nonFiniteA == 0 && nonFiniteB == 0; }
};

// What a comparison is checked against (compare's --fail-* flags); an unset one is not checked.
struct CompareThresholds {
  std::optional<double> minPsnrDb, maxRmse;
  std::optional<double> maxAbs;  // colour, and alpha on its own
  bool any() const { return minPsnrDb || maxRmse || maxAbs; }
  // Each threshold `r` fails, in the words of compare's verdict line ("psnr_db < 45",
  // "max_abs_alpha > 0.1"); with any threshold a pixel that is not finite fails too, whatever the
  // numbers. Empty: passed, or nothing was checked.
  std::vector<std::string> failures(const CompareResult& r) const;
};
// "not finite: 3 pixels of A, 0 of B (NaN or inf, read as 0)".
std::string nonFiniteText(const CompareResult& r);
// The largest difference of alpha as text ("0.25"), or why it was not compared.
std::string alphaText(const CompareResult& r);

// A comparison fed rows top to bottom, a band at a time: the pixel statistics accumulate row by
// row and SSIM's 8-row windows are taken as their last row arrives, from the 8 rows kept. Its
// sums are the whole images' sums in the same order, so the result is compareImages' bit for bit,
// in memory that does not grow with the height.
class RowComparison {
 public:
  // InputError if the sizes differ.
  RowComparison(int widthA, int heightA, int widthB, int heightB, const CompareOptions& options = {});
  // The next `count` rows of each image (RGBA floats, width × count × 4).
  void addRows(const float* a, const float* b, int count);
  // Once every row is in; InputError if no pixel is compared.
  CompareResult result() const;

 private:
  void addRow(const float* a, const float* b);
  void addSsimWindows(int top);
  struct LumaSums {
    double a = 0, b = 0, aa = 0, bb = 0, ab = 0;
    double ssim(double n) const;
  };
  int width_, height_, rows_ = 0;
  CompareOptions options_;
  CompareResult r_;
  double sumSq_ = 0.0, ssimSum_ = 0.0;
  long over_ = 0;
  int windows_ = 0;
  std::vector<float> keptA_, keptB_;  // the last 8 rows, row y at (y mod 8)
  std::vector<float> finiteA_, finiteB_;  // the row being added, non-finite values made 0
  LumaSums whole_;                     // of every compared pixel: SSIM when no window fits
};

// Throws InputError if the sizes differ or no pixel is compared.
CompareResult compareImages(const ImageRGBA& a, const ImageRGBA& b, const CompareOptions& options = {});
// The same, reading both images a band of rows at a time (ImageRowReader): memory for a few rows
// of each, whatever their height. Reads both to the end. InputError for a file that holds no
// colour (ImageRowReader::requireColour).
CompareResult compareImageRows(ImageRowReader& a, ImageRowReader& b, const CompareOptions& options = {});
// Both images read whole (for a heat map, or to downsample one), with compareImageRows' checks;
// `nonFinite` gets each image's count of pixels that were not finite.
struct ColourImagePair {
  ImageRGBA a, b;
  long nonFiniteA = 0, nonFiniteB = 0;
  bool alphaA = true, alphaB = true;  // whether each file has an alpha channel
};
ColourImagePair readColourImages(ImageRowReader& a, ImageRowReader& b);
// compareImages of a pair readColourImages read, its counts of non-finite pixels included.
CompareResult compareImagePair(const ColourImagePair& pair, const CompareOptions& options = {});
// What compareImageRows holds at once besides the readers' own state.
int64_t imageRowsCompareBytes(const ImageRowReader& a, const ImageRowReader& b);
// |a − b| (max over channels) as a heat map: black 0 → red → yellow → white at `scale`.
ImageRGBA differenceHeatmap(const ImageRGBA& a, const ImageRGBA& b, double scale);
// A scalar field as the same heat ramp (black 0 → red → yellow → white at `scale`); NaN is
// drawn transparent black.
ImageRGBA scalarHeatmap(const std::vector<float>& values, int width, int height, double scale);
nlohmann::json compareResultToJson(const CompareResult& r);

// Each n×n block of `large` averaged, every channel: a POV-Ray job's render (n× the image for
// n² samples a pixel, one sample per grid point of docs/conventions.md §2) brought to the image's
// size, as omnicam's POV-Ray engine reduces it. InputError unless n divides both sides.
ImageRGBA boxDownsample(const ImageRGBA& large, int n);
// The factor by which `large` is a whole multiple of `small` in both directions, if it is one (≥ 2).
std::optional<int> wholeMultiple(int smallWidth, int smallHeight, int largeWidth, int largeHeight);

}  // namespace omnicam
