// The recording-camera model against closed forms: identity, vignetting's falloff, the variance
// of shot noise, seeding, and strict parameters.
#include "recording_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "errors.h"

namespace omnicam {
namespace {

ImageRGBA uniform(int size, float value) {
  ImageRGBA image(size, size);
  for (size_t p = 0; p < image.pixels.size(); p += 4)
    image.pixels[p] = image.pixels[p + 1] = image.pixels[p + 2] = value, image.pixels[p + 3] = 1.0f;
  return image;
}

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
  const int n = 101;
  const ImageRGBA out = recordFrame(camera, uniform(n, 0.6f), 0);
  const double halfDiagonalSquared = 0.5 * n * n;
  for (const auto& [i, j] : {std::pair{50, 50}, std::pair{0, 0}, std::pair{100, 50}, std::pair{20, 70}}) {
    const double dx = i + 0.5 - 0.5 * n, dy = j + 0.5 - 0.5 * n;
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

TEST(RecordingCamera, ParametersAreStrict) {
  // Every field away from its default and from the webcam's, through JSON text and back.
  RecordingCamera camera;
  camera.exposureEv = -1.25;
  camera.whiteBalance = {1.3, 0.95, 0.7};
  camera.vignetting = 1.0;
  camera.fullWellElectrons = 1234.5;
  camera.readNoise = 0.0125;
  camera.jpegQuality = 100;
  camera.seed = UINT64_MAX;
  const nlohmann::json written = recordingCameraToJson(camera);
  EXPECT_EQ(written.size(), 7u);
  const RecordingCamera back = recordingCameraFromJson(nlohmann::json::parse(written.dump()), "recording");
  EXPECT_EQ(back.exposureEv, camera.exposureEv);
  EXPECT_EQ(back.whiteBalance, camera.whiteBalance);
  EXPECT_EQ(back.vignetting, camera.vignetting);
  EXPECT_EQ(back.fullWellElectrons, camera.fullWellElectrons);
  EXPECT_EQ(back.readNoise, camera.readNoise);
  EXPECT_EQ(back.jpegQuality, camera.jpegQuality);
  EXPECT_EQ(back.seed, camera.seed);
  // Fields left out keep their defaults.
  const RecordingCamera defaults = recordingCameraFromJson(nlohmann::json::object(), "recording");
  EXPECT_EQ(defaults.exposureEv, 0.0);
  EXPECT_EQ(defaults.whiteBalance, (std::array<double, 3>{1.0, 1.0, 1.0}));
  EXPECT_EQ(defaults.jpegQuality, 0);
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_THROW(recordingCameraFromJson({{"exposure", 1.0}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"vignetting", 1.5}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"jpeg_quality", 101}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"jpeg_quality", 80.5}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"white_balance", {1, 0, 1}}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"seed", -1}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"read_noise", "0.1"}}, "recording"), InputError);
}

}  // namespace
}  // namespace omnicam
