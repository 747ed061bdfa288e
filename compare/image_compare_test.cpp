#include "image_compare.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace omnicam
