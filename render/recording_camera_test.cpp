// The recording-camera model against closed forms: identity, vignetting's falloff, the variance
// of shot noise, seeding, and strict parameters.
#include "recording_camera.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(RecordingCamera, BeyondTheRimStaysBlackAndJpegRoundTrips) {
  RecordingCamera camera = RecordingCamera::webcam();
  ImageRGBA in = uniform(64, 0.4f);
  for (int i = 0; i < 64; ++i) in.at(i, 0)[0] = in.at(i, 0)[1] = in.at(i, 0)[2] = in.at(i, 0)[3] = 0.0f;
  const ImageRGBA out = recordFrame(camera, in, 0);
  for (int i = 0; i < 64; ++i) EXPECT_EQ(out.at(i, 0)[0], 0.0f);
  // Warm white balance: red above blue on a grey input.
  EXPECT_GT(out.at(32, 32)[0], out.at(32, 32)[2]);
}

TEST(RecordingCamera, ParametersAreStrict) {
  EXPECT_NO_THROW(recordingCameraFromJson(recordingCameraToJson(RecordingCamera::webcam()), "recording"));
  EXPECT_THROW(recordingCameraFromJson({{"exposure", 1.0}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"vignetting", 1.5}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"jpeg_quality", 101}}, "recording"), InputError);
  EXPECT_THROW(recordingCameraFromJson({{"white_balance", {1, 0, 1}}}, "recording"), InputError);
}

}  // namespace
}  // namespace omnicam
