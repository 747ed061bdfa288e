#include "image_compare.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "errors.h"

namespace omnicam {
namespace {

ImageRGBA noiseImage(int seed, float alpha) {
  ImageRGBA img(64, 48);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t p = 0; p < img.pixels.size(); ++p) img.pixels[p] = (p % 4 == 3) ? alpha : u(rng);
  return img;
}

// RGB only: we compare colour, not alpha (OIIO's compare covers every channel of a buffer).
OIIO::ImageBuf toRgbBuf(const ImageRGBA& img) {
  std::vector<float> rgb;
  for (size_t p = 0; p < img.pixels.size(); p += 4) rgb.insert(rgb.end(), &img.pixels[p], &img.pixels[p] + 3);
  OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT));
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, rgb.data());
  return buf;
}

TEST(ImageCompare, AgreesWithOpenImageIOsCompare) {
  const ImageRGBA a = noiseImage(1, 1.0f);
  ImageRGBA b = a;
  for (size_t p = 0; p < b.pixels.size(); p += 7)
    if (p % 4 != 3) b.pixels[p] += 0.01f * static_cast<float>(p % 5);  // colour only
  const CompareResult ours = compareImages(a, b);
  const auto theirs = OIIO::ImageBufAlgo::compare(toRgbBuf(a), toRgbBuf(b), 1.0f, 1.0f);
  EXPECT_NEAR(ours.rmse, theirs.rms_error, 1e-7);
  EXPECT_NEAR(ours.psnrDb, 20.0 * std::log10(1.0 / theirs.rms_error), 1e-4);  // PSNR for peak 1
  EXPECT_NEAR(ours.maxAbs, theirs.maxerror, 1e-6);
  EXPECT_EQ(ours.maxI, theirs.maxx);
  EXPECT_EQ(ours.maxJ, theirs.maxy);
}

TEST(ImageCompare, IdenticalImagesAndKnownOffsets) {
  const ImageRGBA a = noiseImage(2, 1.0f);
  const CompareResult same = compareImages(a, a);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_TRUE(std::isinf(same.psnrDb));
  EXPECT_NEAR(same.ssim, 1.0, 1e-12);
  ImageRGBA b = a;
  for (size_t p = 0; p < b.pixels.size(); ++p)
    if (p % 4 != 3) b.pixels[p] += 0.1f;  // uniform offset: RMSE 0.1 → PSNR 20 dB, every pixel over tol
  const CompareResult off = compareImages(a, b);
  EXPECT_NEAR(off.rmse, 0.1, 1e-6);
  EXPECT_NEAR(off.psnrDb, 20.0, 1e-4);
  EXPECT_DOUBLE_EQ(off.fracOverTol, 1.0);
  EXPECT_LT(off.ssim, 1.0);
}

TEST(ImageCompare, ImagesTooSmallForAWindowAreOneWindow) {
  // 5×5: no 8×8 window fits, so SSIM is Wang et al.'s formula over all 25 pixels' luminance.
  // Black against a ramp: means 0 and m, variances 0 and v, covariance 0, so
  // SSIM = c1·c2 / ((m² + c1)(v + c2)), which once came out as 1.
  ImageRGBA black(5, 5), ramp(5, 5);
  double sum = 0, sumSq = 0;
  for (int p = 0; p < 25; ++p) {
    black.pixels[4 * p + 3] = ramp.pixels[4 * p + 3] = 1.0f;
    const float v = static_cast<float>(p) / 24.0f;
    for (int c = 0; c < 3; ++c) ramp.pixels[4 * p + c] = v;
    const double luminance = (0.2126 + 0.7152 + 0.0722) * v;
    sum += luminance, sumSq += luminance * luminance;
  }
  const double mean = sum / 25, variance = sumSq / 25 - mean * mean, c1 = 1e-4, c2 = 9e-4;
  EXPECT_NEAR(compareImages(black, ramp).ssim, c1 * c2 / ((mean * mean + c1) * (variance + c2)), 1e-12);
  EXPECT_NEAR(compareImages(ramp, ramp).ssim, 1.0, 1e-12);
  EXPECT_NEAR(compareImages(ImageRGBA(1, 1), ImageRGBA(1, 1)).ssim, 1.0, 1e-12);
}

TEST(ImageCompare, DiscOnlySkipsPixelsBeyondTheRim) {
  ImageRGBA a = noiseImage(3, 1.0f), b = a;
  a.at(0, 0)[3] = 0.5f;  // a rim pixel in one image
  b.at(0, 0)[0] += 0.5f;
  CompareOptions disc;
  disc.discOnly = true;
  EXPECT_EQ(compareImages(a, b, disc).maxAbs, 0.0);
  EXPECT_GT(compareImages(a, b).maxAbs, 0.4);
  EXPECT_THROW(compareImages(a, noiseImage(4, 0.0f), disc), InputError);  // nothing left
  EXPECT_THROW(compareImages(a, ImageRGBA(10, 10)), InputError);         // sizes differ
}

// The whole-image comparison as it was before rows were streamed (issue #45), kept here as the
// reference the streamed one must match bit for bit: the same sums in the same order.
CompareResult wholeImageReference(const ImageRGBA& a, const ImageRGBA& b, const CompareOptions& options) {
  const auto included = [&](int i, int j) { return !options.discOnly || (a.at(i, j)[3] >= 0.999f && b.at(i, j)[3] >= 0.999f); };
  CompareResult r;
  double sumSq = 0.0;
  long over = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      if (!included(i, j)) continue;
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
  r.rmse = std::sqrt(sumSq / (3.0 * r.pixels));
  r.psnrDb = r.rmse > 0.0 ? 20.0 * std::log10(1.0 / r.rmse) : INFINITY;
  r.fracOverTol = static_cast<double>(over) / r.pixels;
  const auto luma = [](const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; };
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double sum = 0.0;
  int windows = 0;
  for (int y = 0; y + 8 <= a.height; y += 4)
    for (int x = 0; x + 8 <= a.width; x += 4) {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      bool all = true;
      for (int j = y; j < y + 8 && all; ++j)
        for (int i = x; i < x + 8; ++i) {
          if (!included(i, j)) {
            all = false;
            break;
          }
          const double va = luma(a.at(i, j)), vb = luma(b.at(i, j));
          sa += va, sb += vb, saa += va * va, sbb += vb * vb, sab += va * vb;
        }
      if (!all) continue;
      const double n = 64, ma = sa / n, mb = sb / n;
      const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  if (windows) {
    r.ssim = sum / windows;
    return r;
  }
  // No window fits: the compared pixels as one.
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i)
      if (included(i, j)) {
        const double va = luma(a.at(i, j)), vb = luma(b.at(i, j));
        sa += va, sb += vb, saa += va * va, sbb += vb * vb, sab += va * vb;
      }
  const double n = static_cast<double>(r.pixels), ma = sa / n, mb = sb / n;
  const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
  r.ssim = ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
  return r;
}

void expectIdentical(const CompareResult& got, const CompareResult& want, const std::string& what) {
  // Bit for bit: == on doubles (inf == inf for identical images).
  EXPECT_EQ(got.rmse, want.rmse) << what;
  EXPECT_EQ(got.psnrDb, want.psnrDb) << what;
  EXPECT_EQ(got.ssim, want.ssim) << what;
  EXPECT_EQ(got.maxAbs, want.maxAbs) << what;
  EXPECT_EQ(got.fracOverTol, want.fracOverTol) << what;
  EXPECT_EQ(got.maxI, want.maxI) << what;
  EXPECT_EQ(got.maxJ, want.maxJ) << what;
  EXPECT_EQ(got.pixels, want.pixels) << what;
}

// A render-like pair: smooth gradients, noise in B, a disc of alpha 1 with a soft rim.
std::pair<ImageRGBA, ImageRGBA> discPair(int width, int height, int seed) {
  ImageRGBA a(width, height), b(width, height);
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double r = std::hypot(i - width / 2.0, j - height / 2.0) / (0.45 * std::min(width, height));
      const float alpha = r < 1.0 ? 1.0f : r < 1.1 ? static_cast<float>((1.1 - r) / 0.1) : 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float v = static_cast<float>(0.5 + 0.4 * std::sin(0.3 * i + 0.2 * j + c)) * alpha;
        a.at(i, j)[c] = v;
        b.at(i, j)[c] = std::clamp(v + noise(rng), 0.0f, 1.0f) * alpha;
      }
      a.at(i, j)[3] = b.at(i, j)[3] = alpha;
    }
  return {a, b};
}

// Rows fed in bands of any height give the whole-image comparison's numbers bit for bit, with and
// without the disc, on sizes that are and are not multiples of SSIM's window and stride.
TEST(ImageCompare, RowsInBandsGiveTheWholeImageResultBitForBit) {
  int checked = 0;
  for (const auto& [width, height] : std::vector<std::pair<int, int>>{{8, 8}, {37, 29}, {64, 48}, {9, 23}, {40, 11}})
    for (const bool disc : {false, true}) {
      const auto [a, b] = discPair(width, height, width * height);
      CompareOptions options;
      options.discOnly = disc;
      options.tolerance = 0.01;
      const CompareResult want = wholeImageReference(a, b, options);
      ASSERT_GT(want.pixels, 0);
      const std::string what = std::to_string(width) + "x" + std::to_string(height) + (disc ? " disc" : "");
      expectIdentical(compareImages(a, b, options), want, what + " whole");
      for (const int band : {1, 3, 4, 7, 8, 13}) {
        RowComparison rows(width, height, width, height, options);
        for (int first = 0; first < height; first += band) {
          const int count = std::min(band, height - first);
          rows.addRows(a.at(0, first), b.at(0, first), count);
        }
        expectIdentical(rows.result(), want, what + " band " + std::to_string(band));
        ++checked;
      }
      // The SSIM is a real one: below 1 for the noisy pair (windows were taken).
      if (!disc) {
        EXPECT_LT(want.ssim, 1.0) << what;
      }
    }
  EXPECT_EQ(checked, 60);
}

// From files through OpenImageIO's scanline reads (PNG: sRGB 8-bit, straight alpha; EXR: linear
// float): the same numbers as decoding both files whole.
TEST(ImageCompare, StreamedFilesGiveTheWholeImageResultBitForBit) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_compare_rows_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto [a, b] = discPair(77, 70, 5);  // 70 rows: two full bands of 32 and a short one
  for (const char* ext : {".png", ".exr"}) {
    const std::string pathA = (dir / (std::string("a") + ext)).string(), pathB = (dir / (std::string("b") + ext)).string();
    writeImageAtomic(pathA, a);
    writeImageAtomic(pathB, b);
    for (const bool disc : {false, true}) {
      CompareOptions options;
      options.discOnly = disc;
      const CompareResult want = wholeImageReference(readImage(pathA), readImage(pathB), options);
      ImageRowReader rowsA = ImageRowReader::openFile(pathA), rowsB = ImageRowReader::openFile(pathB);
      expectIdentical(compareImageRows(rowsA, rowsB, options), want, std::string(ext) + (disc ? " disc" : ""));
    }
  }
  // Sizes that differ are refused before any row is read.
  writeImageAtomic((dir / "small.png").string(), ImageRGBA(10, 10));
  ImageRowReader rowsA = ImageRowReader::openFile((dir / "a.png").string()), small = ImageRowReader::openFile((dir / "small.png").string());
  EXPECT_THROW(compareImageRows(rowsA, small), InputError);
  fs::remove_all(dir);
}

// A NaN or an infinity is counted, in memory and read from a file (where it decodes as 0), and
// alpha has its own largest difference: a render that differs only there is not identical.
TEST(ImageCompare, NonFinitePixelsAreCountedAndAlphaIsCompared) {
  const ImageRGBA a = noiseImage(3, 1.0f);
  ImageRGBA b = a;
  b.at(5, 7)[1] = std::numeric_limits<float>::quiet_NaN();
  b.at(9, 2)[3] = std::numeric_limits<float>::infinity();
  const CompareResult inMemory = compareImages(a, b);
  EXPECT_EQ(inMemory.nonFiniteA, 0);
  EXPECT_EQ(inMemory.nonFiniteB, 2);
  EXPECT_FALSE(inMemory.allFinite());
  EXPECT_EQ(inMemory.pixels, 64 * 48);  // compared as 0, as a file's decode
  EXPECT_GT(inMemory.rmse, 0.0);
  EXPECT_TRUE(std::isfinite(inMemory.ssim));
  ImageRGBA c = a;
  c.at(11, 13)[3] = 0.25f;  // alpha only: the colours are equal
  const CompareResult alphaOnly = compareImages(a, c);
  EXPECT_EQ(alphaOnly.maxAbs, 0.0);
  EXPECT_DOUBLE_EQ(alphaOnly.maxAbsAlpha, 0.75);
  EXPECT_TRUE(alphaOnly.allFinite());

  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_compare_nan_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string pathA = (dir / "a.exr").string(), pathB = (dir / "b.exr").string(), rays = (dir / "rays.exr").string();
  writeImageAtomic(pathA, a);
  writeImageAtomic(pathB, b);
  ImageRowReader rowsA = ImageRowReader::openFile(pathA), rowsB = ImageRowReader::openFile(pathB);
  const CompareResult fromFiles = compareImageRows(rowsA, rowsB);
  EXPECT_EQ(fromFiles.nonFiniteA, 0);
  EXPECT_EQ(fromFiles.nonFiniteB, 2);
  EXPECT_EQ(fromFiles.pixels, 64 * 48);  // decoded as 0, compared as 0
  EXPECT_EQ(fromFiles.rmse, inMemory.rmse);  // the same numbers either way
  EXPECT_EQ(fromFiles.ssim, inMemory.ssim);
  EXPECT_EQ(fromFiles.maxAbsAlpha, inMemory.maxAbsAlpha);
  ImageRowReader wholeA = ImageRowReader::openFile(pathA), wholeB = ImageRowReader::openFile(pathB);
  const ColourImagePair pair = readColourImages(wholeA, wholeB);
  EXPECT_EQ(compareImagePair(pair).nonFiniteB, 2);
  // A table of data is no colour image, though its first three channels would read as one.
  const std::vector<float> table(64 * 48 * 6, 0.5f);
  const std::vector<unsigned char> bytes =
      encodeDataExr(rays, 64, 48, {"origin.X", "origin.Y", "origin.Z", "direction.X", "direction.Y", "direction.Z"}, table.data());
  std::ofstream(rays, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  ImageRowReader table1 = ImageRowReader::openFile(rays), colour = ImageRowReader::openFile(pathA);
  EXPECT_FALSE(table1.holdsColour());
  EXPECT_TRUE(colour.holdsColour());
  try {
    compareImageRows(colour, table1);
    ADD_FAILURE() << "a table of rays was compared as colour";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a colour image: its first channels, \"direction.X\", \"direction.Y\", \"direction.Z\" (of 6)"),
              std::string::npos)
        << e.what();
  }
  // Colour channels as other tools name them are colour; a grey or a single colour channel too.
  for (const std::vector<std::string>& names : std::vector<std::vector<std::string>>{
           {"r", "g", "b"}, {"Red", "Green", "Blue", "Alpha"}, {"C.r", "C.g", "C.b"}, {"Y"}, {"Y", "A"}, {"R"}}) {
    const std::string file = (dir / "named.exr").string();
    const std::vector<float> values(16 * 16 * names.size(), 0.25f);
    const std::vector<unsigned char> encoded = encodeDataExr(file, 16, 16, names, values.data());
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(encoded.data()), static_cast<std::streamsize>(encoded.size()));
    EXPECT_TRUE(ImageRowReader::openFile(file).holdsColour()) << names[0];
  }
  // Normals' X, Y, Z hold no colour, though one of them is named Y; nor does a layer of depth
  // read before a layer of colour.
  for (const std::vector<std::string>& names : std::vector<std::vector<std::string>>{{"X", "Y", "Z"}, {"depth.Z", "rgb.R", "rgb.G", "rgb.B"}}) {
    const std::string file = (dir / "data.exr").string();
    const std::vector<float> values(16 * 16 * names.size(), 0.25f);
    const std::vector<unsigned char> encoded = encodeDataExr(file, 16, 16, names, values.data());
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(encoded.data()), static_cast<std::streamsize>(encoded.size()));
    EXPECT_FALSE(ImageRowReader::openFile(file).holdsColour()) << names[0];
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// Each 2×2 block's mean, every channel alpha included (a rim pixel's alpha is its imaged share).
TEST(BoxDownsample, AveragesEachBlockInEveryChannel) {
  ImageRGBA large(4, 2);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      float* px = large.at(i, j);
      px[0] = static_cast<float>(i + 4 * j), px[1] = 1.0f, px[2] = static_cast<float>(j), px[3] = i == 0 ? 0.0f : 1.0f;
    }
  const ImageRGBA small = boxDownsample(large, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_FLOAT_EQ(small.at(0, 0)[0], (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(small.at(1, 0)[0], (2 + 3 + 6 + 7) / 4.0f);
  EXPECT_FLOAT_EQ(small.at(0, 0)[1], 1.0f);
  EXPECT_FLOAT_EQ(small.at(0, 0)[2], 0.5f);
  EXPECT_FLOAT_EQ(small.at(0, 0)[3], 0.5f);
  EXPECT_FLOAT_EQ(small.at(1, 0)[3], 1.0f);
  EXPECT_THROW(boxDownsample(large, 3), InputError);
}

TEST(BoxDownsample, AWholeMultipleIsTheSameFactorBothWays) {
  EXPECT_EQ(wholeMultiple(48, 48, 96, 96), 2);
  EXPECT_EQ(wholeMultiple(160, 120, 640, 480), 4);
  EXPECT_EQ(wholeMultiple(48, 48, 48, 48), std::nullopt);   // the same size
  EXPECT_EQ(wholeMultiple(48, 48, 96, 144), std::nullopt);  // 2x one way, 3x the other
  EXPECT_EQ(wholeMultiple(48, 48, 100, 100), std::nullopt);
  EXPECT_EQ(wholeMultiple(96, 96, 48, 48), std::nullopt);   // smaller, not a multiple
}

}  // namespace
}  // namespace omnicam
