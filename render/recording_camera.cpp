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

RecordingCamera recordingCameraFromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": must be an object");
  RecordingCamera camera;
  auto number = [&](const std::string& key, double lo, double hi) {
    const nlohmann::json& v = j.at(key);
    if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
      throw InputError(where + "." + key + ": must be a number in [" + shortNumber(lo) + ", " + shortNumber(hi) + "]");
    return v.get<double>();
  };
  for (const auto& [key, value] : j.items()) {
    if (key == "exposure_ev") camera.exposureEv = number(key, -10, 10);
    else if (key == "white_balance") {
      if (!value.is_array() || value.size() != 3) throw InputError(where + ".white_balance: must be [r, g, b]");
      for (int c = 0; c < 3; ++c) {
        if (!value[c].is_number() || !(value[c].get<double>() > 0 && value[c].get<double>() <= 10))
          throw InputError(where + ".white_balance: gains must be in (0, 10]");
        camera.whiteBalance[c] = value[c].get<double>();
      }
    } else if (key == "vignetting") camera.vignetting = number(key, 0, 1);
    else if (key == "full_well_electrons") camera.fullWellElectrons = number(key, 0, 1e7);
    else if (key == "read_noise") camera.readNoise = number(key, 0, 1);
    else if (key == "jpeg_quality") {
      if (!value.is_number_integer() || value.get<int>() < 0 || value.get<int>() > 100)
        throw InputError(where + ".jpeg_quality: must be an integer in [0, 100] (0: no JPEG)");
      camera.jpegQuality = value.get<int>();
    } else if (key == "seed") {
      if (!value.is_number_unsigned()) throw InputError(where + ".seed: must be a non-negative integer");
      camera.seed = value.get<uint64_t>();
    } else
      throw InputError(where + "." + keySegment(key) + ": unknown field (exposure_ev, white_balance, vignetting, "
                       "full_well_electrons, read_noise, jpeg_quality, seed)");
  }
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
