// The recording-camera model against closed forms: identity, vignetting's falloff, the variance
// of shot noise, seeding, and strict parameters.
#include "recording_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "errors.h"
#include "float_environment.h"
#include "recording_camera_spec.h"

namespace omnicam {
namespace {

ImageRGBA uniform(int width, int height, float value) {
  ImageRGBA image(width, height);
  for (size_t p = 0; p < image.pixels.size(); p += 4)
    image.pixels[p] = image.pixels[p + 1] = image.pixels[p + 2] = value, image.pixels[p + 3] = 1.0f;
  return image;
}
ImageRGBA uniform(int size, float value) { return uniform(size, size, value); }

// The value an 8-bit sRGB code round trip gives.
float quantised(float linear) { return srgbToLinear(std::round(linearToSrgb(linear) * 255.0f) / 255.0f); }

TEST(RecordingCamera, DefaultsOnlyQuantiseToEightBitSrgb) {
  const ImageRGBA in = uniform(8, 0.37f);
  const ImageRGBA out = recordFrame(RecordingCamera{}, in, 0);
  for (size_t p = 0; p < out.pixels.size(); p += 4) EXPECT_FLOAT_EQ(out.pixels[p], quantised(0.37f));
}

TEST(RecordingCamera, VignettingFallsOffWithTheSquaredRadius) {
  RecordingCamera camera;
  camera.vignetting = 0.5;
  // Not square: R is half the diagonal, x and y are told apart.
  const int width = 121, height = 61;
  const ImageRGBA out = recordFrame(camera, uniform(width, height, 0.6f), 0);
  const double halfDiagonalSquared = 0.25 * (width * width + height * height);
  for (const auto& [i, j] : {std::pair{60, 30}, std::pair{0, 0}, std::pair{120, 30}, std::pair{60, 0}, std::pair{20, 50}}) {
    const double dx = i + 0.5 - 0.5 * width, dy = j + 0.5 - 0.5 * height;
    const double expected = 0.6 * (1.0 - 0.5 * (dx * dx + dy * dy) / halfDiagonalSquared);
    EXPECT_NEAR(out.at(i, j)[1], quantised(static_cast<float>(expected)), 1e-6) << i << "," << j;
  }
}

TEST(RecordingCamera, ShotNoiseHasPoissonVarianceAndIsSeeded) {
  RecordingCamera camera;
  camera.fullWellElectrons = 200.0;  // σ = sqrt(x / N) = 0.05 at x = 0.5, far above 8-bit steps
  const ImageRGBA in = uniform(200, 0.5f);
  const ImageRGBA out = recordFrame(camera, in, 3);
  double sum = 0.0, squares = 0.0;
  const size_t n = out.pixels.size() / 4;
  for (size_t p = 0; p < out.pixels.size(); p += 4) sum += out.pixels[p], squares += out.pixels[p] * out.pixels[p];
  const double mean = sum / n, variance = squares / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_NEAR(std::sqrt(variance), std::sqrt(0.5 / 200.0), 0.003);
  EXPECT_EQ(recordFrame(camera, in, 3).pixels, out.pixels);  // same seed and frame: same noise
  EXPECT_NE(recordFrame(camera, in, 4).pixels, out.pixels);
}

// A mirror disc (radius 28 px, alpha 1) holding a smooth colour gradient, black with alpha 0
// beyond it, and one rim pixel half covered (associated alpha: RGB 0.5 × its colour).
ImageRGBA discImage() {
  ImageRGBA image(64, 64);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      float* p = image.at(i, j);
      const bool inside = std::hypot(i + 0.5 - 32.0, j + 0.5 - 32.0) <= 28.0;
      p[0] = inside ? 0.1f + 0.6f * i / 63.0f : 0.0f;
      p[1] = inside ? 0.15f + 0.5f * j / 63.0f : 0.0f;
      p[2] = inside ? 0.4f : 0.0f;
      p[3] = inside ? 1.0f : 0.0f;
    }
  float* rim = image.at(32, 3);  // just outside the disc
  rim[0] = rim[1] = rim[2] = 0.2f, rim[3] = 0.5f;
  return image;
}

// PSNR in 8-bit sRGB codes between a recorded frame and the input, over the disc's pixels at
// most `radius` from its centre.
double psnrInsideDisc(const ImageRGBA& recorded, const ImageRGBA& input, double radius = 28.0) {
  double squares = 0.0;
  int n = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      if (input.at(i, j)[3] < 1.0f || std::hypot(i + 0.5 - 32.0, j + 0.5 - 32.0) > radius) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = 255.0 * (linearToSrgb(recorded.at(i, j)[c]) - linearToSrgb(input.at(i, j)[c]));
        squares += d * d;
        ++n;
      }
    }
  return 10.0 * std::log10(255.0 * 255.0 / (squares / n));
}

TEST(RecordingCamera, BeyondTheRimStaysBlackAndJpegRoundTrips) {
  const ImageRGBA in = discImage();
  // The JPEG round trip alone, decoded and compared with the input in sRGB codes. Quality 80
  // keeps the smooth gradient 12 px or more inside the rim to 47.9 dB (measured; rounding to
  // codes alone: 58 dB), and the whole disc to 32.7 dB (the black beyond the rim rings into its
  // outer pixels, and 4:2:0 chroma smears the edge). It is lossy (not the 8-bit frame), and the
  // quality is used: 20 loses more, 98 less (measured 24.6 and 40.0 dB over the disc).
  RecordingCamera jpeg;
  jpeg.jpegQuality = 80;
  const ImageRGBA decoded = recordFrame(jpeg, in, 0);
  const ImageRGBA codesOnly = recordFrame(RecordingCamera{}, in, 0);
  const double psnr80 = psnrInsideDisc(decoded, in), interior80 = psnrInsideDisc(decoded, in, 16.0);
  jpeg.jpegQuality = 20;
  const double psnr20 = psnrInsideDisc(recordFrame(jpeg, in, 0), in);
  jpeg.jpegQuality = 98;
  const double psnr98 = psnrInsideDisc(recordFrame(jpeg, in, 0), in);
  std::printf("JPEG round trip over the disc: %.1f dB (quality 20), %.1f dB (80; %.1f dB 12 px inside the rim), "
              "%.1f dB (98), %.1f dB (no JPEG)\n", psnr20, psnr80, interior80, psnr98, psnrInsideDisc(codesOnly, in));
  EXPECT_GT(interior80, 45.0);
  EXPECT_GT(psnr80, 30.0);
  EXPECT_NE(decoded.pixels, codesOnly.pixels);
  EXPECT_LT(psnr20, psnr80 - 3.0);
  EXPECT_GT(psnr98, psnr80 + 3.0);

  // Everything the webcam does: beyond the rim stays black whatever JPEG rings into it, and
  // alpha is kept.
  const ImageRGBA out = recordFrame(RecordingCamera::webcam(), in, 0);
  int black = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const float* o = out.at(i, j);
      EXPECT_EQ(o[3], in.at(i, j)[3]) << i << "," << j;
      if (in.at(i, j)[3] > 0.0f) continue;
      EXPECT_EQ(o[0], 0.0f) << i << "," << j;
      EXPECT_EQ(o[1], 0.0f) << i << "," << j;
      EXPECT_EQ(o[2], 0.0f) << i << "," << j;
      ++black;
    }
  EXPECT_GT(black, 1000);
  // The half-covered rim pixel keeps its colour (associated alpha): without noise or JPEG,
  // exactly alpha × the 8-bit code of its straight colour.
  const float* rim = codesOnly.at(32, 3);
  EXPECT_FLOAT_EQ(rim[0], 0.5f * quantised(0.4f));
  EXPECT_FLOAT_EQ(rim[3], 0.5f);
}

TEST(RecordingCamera, WhiteBalanceExposureAndVignettingScaleTheMeanColour) {
  // The webcam without its JPEG (tested above) on a uniform grey: the mean over a 16×16 patch at
  // the centre is, per channel, 0.4 · 2^0.3 · white balance · mean vignetting. Shot and read
  // noise average out: σ ≈ 0.015 per pixel, 0.001 for the mean of 256 (0.25 %); bound 0.6 %.
  RecordingCamera camera = RecordingCamera::webcam();
  camera.jpegQuality = 0;
  const int n = 64;
  const ImageRGBA out = recordFrame(camera, uniform(n, 0.4f), 0);
  double vignette = 0.0, mean[3] = {0.0, 0.0, 0.0};
  for (int j = 24; j < 40; ++j)
    for (int i = 24; i < 40; ++i) {
      const double dx = i + 0.5 - 0.5 * n, dy = j + 0.5 - 0.5 * n;
      vignette += (1.0 - 0.35 * (dx * dx + dy * dy) / (0.5 * n * n)) / 256.0;
      for (int c = 0; c < 3; ++c) mean[c] += out.at(i, j)[c] / 256.0;
    }
  const double wb[3] = {1.12, 1.0, 0.84};
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.4 * std::exp2(0.3) * wb[c] * vignette;
    std::printf("channel %d: mean %.4f, closed form %.4f\n", c, mean[c], expected);
    EXPECT_NEAR(mean[c], expected, 0.006 * expected) << "channel " << c;
  }
}

// A camera whose tone curve is linear (γ = 1): its 8-bit codes are the sensor's values.
RecordingCamera linearCodes() {
  RecordingCamera camera;
  camera.tone = ToneCurve::Gamma;
  camera.gamma = 1.0;
  return camera;
}

// The sensor value behind each pixel's code (linear tone curve), per channel.
double sensorValue(const ImageRGBA& out, int i, int j, int c) { return std::round(linearToSrgb(out.at(i, j)[c]) * 255.0f) / 255.0; }

TEST(RecordingCamera, AFlatFieldsNoiseVarianceIsShotPlusReadPlusQuantisation) {
  // Closed form: Var = v / N (Poisson electrons over full well) + σ_read² + q² / 12, q = 1/255.
  RecordingCamera camera = linearCodes();
  camera.fullWellElectrons = 400.0;
  camera.readNoise = 0.01;
  const double v = 0.3;
  const int n = 256;
  const ImageRGBA out = recordFrame(camera, uniform(n, static_cast<float>(v)), 5);
  double sum = 0.0, squares = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = sensorValue(out, i, j, 1);
      sum += x, squares += x * x;
    }
  const double count = static_cast<double>(n) * n, mean = sum / count, variance = squares / count - mean * mean;
  const double expected = v / 400.0 + 0.01 * 0.01 + 1.0 / (255.0 * 255.0 * 12.0);
  std::printf("flat field: variance %.4g, closed form %.4g\n", variance, expected);
  EXPECT_NEAR(mean, v, 0.002);
  EXPECT_NEAR(variance, expected, 0.03 * expected);  // 65536 samples: the variance's own spread is 0.6 %
}

TEST(RecordingCamera, RowNoiseIsOneOffsetPerRow) {
  RecordingCamera camera = linearCodes();
  camera.rowNoise = 0.02;
  const int n = 256;
  const ImageRGBA out = recordFrame(camera, uniform(n, 0.5f), 2);
  double sum = 0.0, squares = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 1; i < n; ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at(i, j)[c], out.at(0, j)[c]) << "row " << j << " is not one value";
    for (int c = 1; c < 3; ++c) ASSERT_EQ(out.at(0, j)[c], out.at(0, j)[0]) << "row " << j << ": one offset in R, G and B";
    const double x = sensorValue(out, 0, j, 0);
    sum += x, squares += x * x;
  }
  const double mean = sum / n, sigma = std::sqrt(squares / n - mean * mean);
  std::printf("row offsets: σ %.4f (closed form 0.02, plus 8-bit steps)\n", sigma);
  EXPECT_NEAR(sigma, std::sqrt(0.02 * 0.02 + 1.0 / (255.0 * 255.0 * 12.0)), 0.2 * 0.02);  // 256 rows: ±9 % at 1σ
}

TEST(RecordingCamera, DemosaicingAConstantColourIsExactForEveryPatternAndMethod) {
  // Each pattern samples its colour per site (bayerColourAt); OpenCV's demosaicing must give the
  // constant colour back at every pixel: a pattern named wrongly would swap the channels.
  const double colour[3] = {0.2, 0.55, 0.8};
  ImageRGBA in(32, 32);
  for (size_t p = 0; p < in.pixels.size(); p += 4)
    for (int c = 0; c < 4; ++c) in.pixels[p + static_cast<size_t>(c)] = c < 3 ? static_cast<float>(colour[c]) : 1.0f;
  for (const BayerPattern pattern : {BayerPattern::RGGB, BayerPattern::BGGR, BayerPattern::GRBG, BayerPattern::GBRG})
    for (const DemosaicMethod method : {DemosaicMethod::Bilinear, DemosaicMethod::Vng, DemosaicMethod::EdgeAware}) {
      RecordingCamera camera = linearCodes();
      camera.bayer = pattern;
      camera.demosaic = method;
      const ImageRGBA out = recordFrame(camera, in, 0);
      const double rawScale = method == DemosaicMethod::Vng ? 255.0 : 65535.0;
      for (int c = 0; c < 3; ++c) {
        const double raw = std::round(colour[c] * rawScale) / rawScale;
        const double expected = std::round(raw * 255.0) / 255.0;
        for (int j = 0; j < 32; ++j)
          for (int i = 0; i < 32; ++i)
            ASSERT_NEAR(sensorValue(out, i, j, c), expected, 1e-9)
                << "pattern " << static_cast<int>(pattern) << " method " << static_cast<int>(method) << " channel " << c
                << " at " << i << "," << j;
      }
    }
  // The layouts themselves: RGGB has red at (0, 0) and blue at (1, 1); GBRG green at (0, 0), blue at (1, 0).
  EXPECT_EQ(bayerColourAt(BayerPattern::RGGB, 0, 0), 0);
  EXPECT_EQ(bayerColourAt(BayerPattern::RGGB, 1, 1), 2);
  EXPECT_EQ(bayerColourAt(BayerPattern::GBRG, 1, 0), 2);
  EXPECT_EQ(bayerColourAt(BayerPattern::GRBG, 1, 0), 0);
  EXPECT_EQ(bayerColourAt(BayerPattern::BGGR, 2, 2), 2);
}

LinearPlanes pointSpread(int n, double x, double y, double sigma) {
  LinearPlanes planes;
  planes.width = planes.height = n;
  for (auto& plane : planes.rgb) plane.assign(static_cast<size_t>(n) * n, 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double dx = i + 0.5 - x, dy = j + 0.5 - y;
      const float v = sigma > 0 ? static_cast<float>(std::exp(-0.5 * (dx * dx + dy * dy) / (sigma * sigma))) : (dx == 0 && dy == 0);
      for (int c = 0; c < 3; ++c) planes.at(c, i, j) = v;
    }
  return planes;
}

// A channel's sum and its centroid's offset from (cx, cy), and its second moment in x about it.
struct Moments {
  double sum = 0, x = 0, y = 0, xx = 0;
};
Moments momentsOf(const LinearPlanes& planes, int c, double cx, double cy) {
  Moments m;
  for (int j = 0; j < planes.height; ++j)
    for (int i = 0; i < planes.width; ++i) {
      const double v = planes.at(c, i, j);
      m.sum += v, m.x += v * (i + 0.5 - cx), m.y += v * (j + 0.5 - cy);
    }
  m.x /= m.sum, m.y /= m.sum;
  for (int j = 0; j < planes.height; ++j)
    for (int i = 0; i < planes.width; ++i) m.xx += planes.at(c, i, j) * std::pow(i + 0.5 - cx - m.x, 2) / m.sum;
  return m;
}

TEST(RecordingCamera, LateralChromaticAberrationMovesRedOutAndBlueInByTheRadius) {
  // A spot at radius r = 40 px from the centre: red's centroid at r (1 + a), blue's at r (1 − a),
  // green's at r.
  const int n = 128;
  const double a = 0.02, r = 40.0;
  LinearPlanes planes = pointSpread(n, 64.0 + r * 0.6, 64.0 - r * 0.8, 1.5);
  applyChromaticAberration(planes, a);
  for (const auto& [c, scale] : {std::pair{0, 1 + a}, std::pair{1, 1.0}, std::pair{2, 1 - a}}) {
    const Moments m = momentsOf(planes, c, 64.0, 64.0);
    std::printf("channel %d: centroid at radius %.4f px (closed form %.4f)\n", c, std::hypot(m.x, m.y), r * scale);
    EXPECT_NEAR(m.x, r * 0.6 * scale, 0.01) << "channel " << c;
    EXPECT_NEAR(m.y, -r * 0.8 * scale, 0.01) << "channel " << c;
  }
}

TEST(RecordingCamera, LensBlurSpreadsAPointByItsKernelsSecondMoment) {
  // A point through a Gaussian PSF of σ: second moment σ² per axis; through a uniform disc of
  // radius R: R²/4 per axis. Both keep the light (sum 1).
  const int n = 65;
  LinearPlanes gaussian = pointSpread(n, 32.5, 32.5, 0.0);
  applyLensBlur(gaussian, 2.5, BlurKernel::Gaussian);
  const Moments g = momentsOf(gaussian, 1, 32.5, 32.5);
  EXPECT_NEAR(g.sum, 1.0, 1e-4);
  EXPECT_NEAR(g.xx, 2.5 * 2.5, 0.02 * 6.25);  // the kernel is cut at 3σ
  LinearPlanes disc = pointSpread(n, 32.5, 32.5, 0.0);
  applyLensBlur(disc, 6.0, BlurKernel::Disc);
  const Moments d = momentsOf(disc, 1, 32.5, 32.5);
  std::printf("second moments: Gaussian %.4f (σ² 6.25), disc %.4f (R²/4 = 9; the cells' discretisation adds about 1 %%)\n", g.xx, d.xx);
  EXPECT_NEAR(d.sum, 1.0, 1e-4);
  EXPECT_NEAR(d.xx, 9.0, 0.02 * 9.0);
  EXPECT_NEAR(d.x, 0.0, 1e-6);
}

// Below a pixel the kernels are what sampling them on whole pixels gives (docs/experiments.md):
// a Gaussian's second moment is Σk²e^(−k²/2σ²) / Σe^(−k²/2σ²) over |k| ≤ ⌈3σ⌉ — σ² from about
// 0.8 px, far less below — and a disc of radius ≤ 0.5 px covers its own cell only.
TEST(RecordingCamera, SubPixelBlurIsTheKernelSampledOnWholePixels) {
  const auto sampledSecondMoment = [](double sigma) {
    const int half = static_cast<int>(std::ceil(3.0 * sigma));
    double weights = 0.0, moment = 0.0;
    for (int k = -half; k <= half; ++k) {
      const double w = std::exp(-k * k / (2.0 * sigma * sigma));
      weights += w, moment += k * k * w;
    }
    return moment / weights;
  };
  for (const auto& [sigma, documented] : {std::pair{0.3, 0.0077}, std::pair{0.5, 0.215}, std::pair{0.8, 0.640}, std::pair{1.0, 0.996}}) {
    LinearPlanes point = pointSpread(15, 7.5, 7.5, 0.0);
    applyLensBlur(point, sigma, BlurKernel::Gaussian);
    const Moments m = momentsOf(point, 1, 7.5, 7.5);
    EXPECT_NEAR(m.xx, sampledSecondMoment(sigma), 1e-5) << sigma;
    EXPECT_NEAR(m.xx, documented, 0.0005) << sigma;
  }
  LinearPlanes halfPixelDisc = pointSpread(15, 7.5, 7.5, 0.0);
  applyLensBlur(halfPixelDisc, 0.5, BlurKernel::Disc);
  EXPECT_FLOAT_EQ(halfPixelDisc.at(1, 7, 7), pointSpread(15, 7.5, 7.5, 0.0).at(1, 7, 7));
  EXPECT_EQ(momentsOf(halfPixelDisc, 1, 7.5, 7.5).xx, 0.0);
}

TEST(RecordingCamera, ATinyDiscKeepsThePointAndBlurAtTheRimAddsNoLight) {
  // A disc radius below every sample's distance from its cell centre is a point: the light stays.
  LinearPlanes point = pointSpread(9, 4.5, 4.5, 0.0);
  applyLensBlur(point, 0.05, BlurKernel::Disc);
  EXPECT_EQ(point.at(1, 4, 4), 1.0f);
  // The mirror disc through blur and aberration: no pixel, rim ones included, comes out brighter
  // than the brightest light in the frame (a rim pixel's colour is its covered part's), and
  // beyond the rim stays black.
  RecordingCamera camera = linearCodes();
  camera.blurRadiusPx = 1.5;
  camera.chromaticAberration = 0.01;
  const ImageRGBA in = discImage(), out = recordFrame(camera, in, 0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < 3; ++c) {
        const float alpha = in.at(i, j)[3];
        if (alpha == 0.0f) ASSERT_EQ(out.at(i, j)[c], 0.0f) << i << "," << j;
        else ASSERT_LE(sensorValue(out, i, j, c) / alpha, 0.7 + 1.0 / 255.0) << i << "," << j << " channel " << c;
      }
}

TEST(RecordingCamera, ToneCurvesFollowTheirClosedForms) {
  RecordingCamera camera;
  EXPECT_NEAR(toneCurveValue(camera, 0.18), 1.055 * std::pow(0.18, 1 / 2.4) - 0.055, 1e-6);  // IEC 61966-2-1
  EXPECT_NEAR(toneCurveValue(camera, 0.002), 12.92 * 0.002, 1e-7);
  camera.tone = ToneCurve::Gamma;
  camera.gamma = 2.0;
  EXPECT_NEAR(toneCurveValue(camera, 0.25), 0.5, 1e-12);
  camera.tone = ToneCurve::Filmic;
  camera.contrast = 1.8;
  // s(x) = x^c / (x^c + (1 − x)^c) of x = v^(1/2.2): mid-grey at 0.5, symmetric, slope c there.
  const double mid = std::pow(0.5, 2.2);
  EXPECT_NEAR(toneCurveValue(camera, mid), 0.5, 1e-12);
  for (double x : {0.1, 0.3, 0.45})
    EXPECT_NEAR(toneCurveValue(camera, std::pow(x, 2.2)) + toneCurveValue(camera, std::pow(1 - x, 2.2)), 1.0, 1e-12);
  const double h = 1e-5;
  EXPECT_NEAR((toneCurveValue(camera, std::pow(0.5 + h, 2.2)) - toneCurveValue(camera, std::pow(0.5 - h, 2.2))) / (2 * h), 1.8, 1e-6);
  EXPECT_EQ(toneCurveValue(camera, 0.0), 0.0);
  EXPECT_EQ(toneCurveValue(camera, 1.0), 1.0);
}

#if defined(__SSE__) || defined(__x86_64__)  // the mode is x86's MXCSR; elsewhere FlushDenormals does nothing
// A frame records the same whatever the calling thread's floating-point mode. Embree leaves
// flush-to-zero and denormals-are-zero set on the threads that built a scene, others keep IEEE
// denormals; a blur of 0.07 px has weights of e^−102 ≈ 5e−45, denormal as floats, and one
// differing value reshuffles every later draw of the noise's stream.
TEST(RecordingCamera, AFrameRecordsTheSameWhateverTheCallersDenormalMode) {
  ImageRGBA in(48, 40);
  for (int j = 0; j < in.height; ++j)
    for (int i = 0; i < in.width; ++i) {
      float* p = in.at(i, j);
      p[0] = 0.02f * (i % 7), p[1] = 0.5f * (j % 3 == 0), p[2] = 0.9f - 0.01f * i, p[3] = 1.0f;
    }
  RecordingCamera camera;
  camera.blurRadiusPx = 0.07;
  camera.fullWellElectrons = 2000.0;
  camera.readNoise = 0.01;
  const unsigned int callers = _mm_getcsr();
  constexpr unsigned int kFlushToZero = FlushDenormals::kFlushToZero, kDenormalsAreZero = FlushDenormals::kDenormalsAreZero;
  _mm_setcsr(callers & ~(kFlushToZero | kDenormalsAreZero));
  const ImageRGBA ieee = recordFrame(camera, in, 5);
  const unsigned int after = _mm_getcsr();
  _mm_setcsr(callers | kFlushToZero | kDenormalsAreZero);
  const ImageRGBA flushed = recordFrame(camera, in, 5);
  _mm_setcsr(callers);
  EXPECT_EQ(after & (kFlushToZero | kDenormalsAreZero), 0u) << "the caller's mode is restored";
  EXPECT_EQ(ieee.pixels, flushed.pixels);
}
#endif

}  // namespace
}  // namespace omnicam
