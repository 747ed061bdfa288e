#include "recording_camera.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "errors.h"
#include "json_fields.h"
#include "number_format.h"

namespace omnicam {

RecordingCamera RecordingCamera::webcam() {
  RecordingCamera camera;
  camera.exposureEv = 0.3;
  camera.whiteBalance = {1.12, 1.0, 0.84};  // balanced for daylight, shooting under warm lamps
  camera.vignetting = 0.35;
  camera.fullWellElectrons = 2500.0;
  camera.readNoise = 0.008;
  camera.jpegQuality = 80;
  return camera;
}

RecordingCamera recordingCameraFromJson(const nlohmann::json& j, const std::string& file, const std::string& where) {
  JsonFields f(j, file, where);
  RecordingCamera camera;
  camera.exposureEv = f.number("exposure_ev", camera.exposureEv, {-10, 10});
  if (f.has("white_balance")) {
    const Vec3 gains = f.vec3("white_balance");
    for (int c = 0; c < 3; ++c) {
      if (!(gains[c] > 0 && gains[c] <= 10)) f.fail("white_balance", "gains must be in (0, 10] (got " + shortNumber(gains[c]) + ")");
      camera.whiteBalance[c] = gains[c];
    }
  }
  camera.vignetting = f.number("vignetting", camera.vignetting, {0, 1});
  camera.fullWellElectrons = f.number("full_well_electrons", camera.fullWellElectrons, {0, 1e7});
  camera.readNoise = f.number("read_noise", camera.readNoise, {0, 1});
  if (f.has("jpeg_quality")) {
    const auto quality = integerInRange(f.raw("jpeg_quality"), 0, 100);
    if (!quality) f.fail("jpeg_quality", "must be an integer in [0, 100] (0: no JPEG) (got " + jsonValueText(f.raw("jpeg_quality")) + ")");
    camera.jpegQuality = static_cast<int>(*quality);
  }
  if (f.has("seed")) {  // any unsigned 64-bit integer, read exactly
    const nlohmann::json& seed = f.raw("seed");
    if (!seed.is_number_unsigned()) f.fail("seed", "must be an integer in [0, 2^64 - 1] (got " + jsonValueText(seed) + ")");
    camera.seed = seed.get<uint64_t>();
  }
  f.finish();
  return camera;
}

nlohmann::json recordingCameraToJson(const RecordingCamera& c) {
  return {{"exposure_ev", c.exposureEv},   {"white_balance", c.whiteBalance}, {"vignetting", c.vignetting},
          {"full_well_electrons", c.fullWellElectrons}, {"read_noise", c.readNoise}, {"jpeg_quality", c.jpegQuality},
          {"seed", c.seed}};
}

ImageRGBA recordFrame(const RecordingCamera& camera, const ImageRGBA& linear, uint64_t frameIndex) {
  // SplitMix-style mixing: neighbouring frame indices give unrelated streams.
  uint64_t mixed = camera.seed + 0x9E3779B97F4A7C15ull * (frameIndex + 1);
  mixed = (mixed ^ (mixed >> 30)) * 0xBF58476D1CE4E5B9ull;
  mixed = (mixed ^ (mixed >> 27)) * 0x94D049BB133111EBull;
  std::mt19937_64 random(mixed ^ (mixed >> 31));
  std::normal_distribution<double> gaussian(0.0, 1.0);

  const int w = linear.width, h = linear.height;
  const double gain = std::exp2(camera.exposureEv);
  const double halfDiagonalSquared = 0.25 * (static_cast<double>(w) * w + static_cast<double>(h) * h);
  cv::Mat codes(h, w, CV_8UC3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const float* p = linear.at(i, j);
      const double alpha = p[3];
      const double dx = i + 0.5 - 0.5 * w, dy = j + 0.5 - 0.5 * h;
      const double vignette = 1.0 - camera.vignetting * (dx * dx + dy * dy) / halfDiagonalSquared;
      cv::Vec3b& out = codes.at<cv::Vec3b>(j, i);
      for (int c = 0; c < 3; ++c) {
        double value = alpha > 0 ? p[c] / alpha * gain * camera.whiteBalance[c] * vignette : 0.0;
        if (alpha > 0 && camera.fullWellElectrons > 0) {
          const double electrons = std::max(0.0, value) * camera.fullWellElectrons;
          value = static_cast<double>(std::poisson_distribution<int64_t>(electrons)(random)) / camera.fullWellElectrons;
        }
        if (alpha > 0 && camera.readNoise > 0) value += camera.readNoise * gaussian(random);
        const float code = linearToSrgb(static_cast<float>(std::clamp(value, 0.0, 1.0)));
        out[2 - c] = static_cast<unsigned char>(std::lround(std::clamp(code, 0.0f, 1.0f) * 255.0f));  // OpenCV: BGR
      }
    }
  if (camera.jpegQuality > 0) {
    std::vector<unsigned char> jpeg;
    cv::imencode(".jpg", codes, jpeg, {cv::IMWRITE_JPEG_QUALITY, camera.jpegQuality});
    codes = cv::imdecode(jpeg, cv::IMREAD_COLOR);
  }
  ImageRGBA recorded(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const float alpha = linear.at(i, j)[3];
      const cv::Vec3b& code = codes.at<cv::Vec3b>(j, i);
      float* out = recorded.at(i, j);
      for (int c = 0; c < 3; ++c) out[c] = alpha * srgbToLinear(code[2 - c] / 255.0f);
      out[3] = alpha;
    }
  return recorded;
}

}  // namespace omnicam
